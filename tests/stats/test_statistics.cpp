// Statistical tests of age vs load. Every stream and offset comes from a fixed
// seed, so each test is deterministic (never flaky); the comments state the
// confidence each margin stands for, had the seeds been drawn at random.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "habuffer/age_experiment.h"
#include "test_support.h"

namespace habuffer {
namespace {

const ExperimentRow& row(const std::vector<ExperimentRow>& rows, Probing probing, Policy policy, double load,
                         OffsetGenerator offsets = OffsetGenerator::Random) {
  for (const auto& r : rows)
    if (r.variant.probing == probing && r.variant.policy == policy && r.load == load && r.variant.offsets == offsets)
      return r;
  throw std::logic_error("row not found");
}

TEST(Statistics, TheMeansConfidenceIntervalIsTSigmaOverTheRootOfN) {
  const std::vector<double> five{1, 2, 3, 4, 5};  // sample sd sqrt(2.5), t95(4) = 2.776
  EXPECT_NEAR(mean_ci95(five), student_t95(4) * std::sqrt(2.5) / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(mean_ci95(five), 1.9632, 1e-3);
  // Four times the samples, same spread: the interval narrows by more than 2x.
  std::vector<double> twenty;
  for (int k = 0; k < 4; ++k) twenty.insert(twenty.end(), five.begin(), five.end());
  EXPECT_LT(mean_ci95(twenty), mean_ci95(five) / 2.0);
  EXPECT_EQ(mean_ci95(std::vector<double>{3.0}), 0.0);
  EXPECT_EQ(mean_ci95(std::vector<double>{2.0, 2.0, 2.0}), 0.0);
}

TEST(Statistics, CoherentRobinHoodSimulatorBuildsTheL32HaBufferTable) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Extent screen{48, 40}, table{60, 40};
    const auto f = test::stream(screen, seed % 2 ? StreamKind::Random : StreamKind::Coherent, 1900, seed);
    SimulatorConfig sc{screen, table, 6, 4, Probing::Coherent, Policy::RobinHood, seed};
    ProbeSimulator sim(sc);
    sim.insert(f);
    HaBuffer b(test::config(screen, table, Layout::L32, 6, 4), OffsetSequence::random(table, 63, seed));
    const Counters n = b.insert(f);
    ASSERT_EQ(n.failed_iter, 0u);
    for (std::uint64_t s = 0; s < b.slot_count(); ++s) ASSERT_EQ(sim.l32_word(s), b.slot(s)) << "slot " << s;
    EXPECT_EQ(sim.totals().counters.stored(), n.stored());
  }
}

// Harness check: one fragment per pixel (distinct keys) and independent
// probing is textbook random probing, whose successful-search cost is
// (1/a) ln(1/(1-a)). The measured mean must fall within its 95% confidence
// interval (10 trials, Student t) widened by 0.5% for the finite table.
TEST(Statistics, DistinctKeysWithIndependentProbingMatchUniformProbingTheory) {
  const Extent screen{256, 256};
  for (double load : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    std::vector<double> means;
    for (std::uint64_t t = 0; t < 10; ++t) {
      // A random subset of distinct pixels, one fragment each.
      std::vector<std::uint32_t> pixels(screen.area());
      std::iota(pixels.begin(), pixels.end(), 0u);
      SplitMix64 rng(100 + t);
      const auto n = static_cast<std::size_t>(load * static_cast<double>(screen.area()));
      std::vector<Fragment> f;
      for (std::size_t i = 0; i < n; ++i) {
        std::swap(pixels[i], pixels[i + rng.below(pixels.size() - i)]);
        f.push_back({pixels[i] % screen.x, pixels[i] / screen.x, rng.unit_float(), 0});
      }
      ProbeSimulator sim({screen, screen, 12, 8, Probing::Independent, Policy::RobinHood, 7 + t});
      sim.insert(f);
      const auto tot = sim.totals();
      double stored = 0, weighted = 0;
      for (std::size_t a = 1; a < tot.age_histogram.size(); ++a) {
        stored += static_cast<double>(tot.age_histogram[a]);
        weighted += static_cast<double>(a * tot.age_histogram[a]);
      }
      ASSERT_EQ(tot.counters.failures(), 0u);
      means.push_back(weighted / stored);
    }
    const double mean = std::accumulate(means.begin(), means.end(), 0.0) / 10.0;
    double ss = 0;
    for (double m : means) ss += (m - mean) * (m - mean);
    const double ci = student_t95(9) * std::sqrt(ss / 9.0 / 10.0);
    const double theory = std::log(1.0 / (1.0 - load)) / load;
    EXPECT_NEAR(mean, theory, ci + 0.005 * theory) << "load " << load << " mean " << mean << " +- " << ci;
  }
}

ExperimentConfig paper_setup(StreamKind kind) {
  ExperimentConfig c;
  // Rasterization-like streams vary more from trial to trial (a few large
  // primitives decide the depth complexity): a larger screen and more trials.
  c.screen = kind == StreamKind::Random ? Extent{128, 128} : Extent{256, 256};
  c.loads = {0.5, 0.8, 0.9};
  c.trials = kind == StreamKind::Random ? 8 : 12;
  c.seed = 3;
  c.stream.kind = kind;
  c.variants = {{Probing::Coherent, Policy::RobinHood, OffsetGenerator::Random},
                {Probing::Coherent, Policy::RobinHood, OffsetGenerator::Farthest},
                {Probing::Independent, Policy::RobinHood, OffsetGenerator::Random},
                {Probing::Coherent, Policy::Fcfs, OffsetGenerator::Random}};
  return c;
}

// Coherence lowers mean age against per-pixel probe sequences: the 95%
// intervals of coherent and independent probing do not overlap, the ratio
// stays in [0.6, 0.95], and both stay above the rank bound (each excess
// interval lies above 0), on random and rasterization-like streams.
TEST(Statistics, CoherentProbingBeatsIndependentProbingAndStaysAboveTheRankBound) {
  for (StreamKind kind : {StreamKind::Random, StreamKind::Coherent}) {
    const auto rows = run_age_experiment(paper_setup(kind));
    for (double load : {0.5, 0.8, 0.9}) {
      SCOPED_TRACE(to_string(kind) + " load " + std::to_string(load));
      const auto& ind = row(rows, Probing::Independent, Policy::RobinHood, load);
      const auto& coh = row(rows, Probing::Coherent, Policy::RobinHood, load);
      EXPECT_LT(coh.mean_age + coh.mean_age_ci95, ind.mean_age - ind.mean_age_ci95);
      EXPECT_GT(coh.mean_age / ind.mean_age, 0.6);
      EXPECT_LT(coh.mean_age / ind.mean_age, 0.95);
      EXPECT_GT(coh.excess - coh.excess_ci95, 0.0);
      EXPECT_GT(ind.excess - ind.excess_ci95, 0.0);
      EXPECT_LT(coh.excess, ind.excess);
      EXPECT_EQ(coh.failures, 0u);
    }
  }
}

// Farthest-point offsets on a table whose sides are powers of two form a
// nested lattice: pixels that differ by a lattice vector probe the same few
// slots in permuted order, so they crowd each other. Mean age rises well
// above random offsets' (95% intervals apart, and over 1.5x at load 0.8).
TEST(Statistics, FarthestOffsetsRaiseMeanAgeOnRandomStreams) {
  const auto rows = run_age_experiment(paper_setup(StreamKind::Random));
  for (double load : {0.5, 0.8}) {
    const auto& rnd = row(rows, Probing::Coherent, Policy::RobinHood, load, OffsetGenerator::Random);
    const auto& far = row(rows, Probing::Coherent, Policy::RobinHood, load, OffsetGenerator::Farthest);
    EXPECT_GT(far.mean_age - far.mean_age_ci95, rnd.mean_age + rnd.mean_age_ci95) << load;
    EXPECT_GT(far.max_age, rnd.max_age) << load;
  }
  EXPECT_GT(row(rows, Probing::Coherent, Policy::RobinHood, 0.8, OffsetGenerator::Farthest).mean_age,
            1.5 * row(rows, Probing::Coherent, Policy::RobinHood, 0.8, OffsetGenerator::Random).mean_age);
}

// The classical Robin Hood result, on coherent hashing: at (nearly) equal
// mean, much smaller variance and maximum than first-come-first-served.
TEST(Statistics, RobinHoodShrinksVarianceAndMaximumAgainstFcfs) {
  const auto rows = run_age_experiment(paper_setup(StreamKind::Random));
  for (double load : {0.5, 0.8, 0.9}) {
    const auto& rh = row(rows, Probing::Coherent, Policy::RobinHood, load);
    const auto& fc = row(rows, Probing::Coherent, Policy::Fcfs, load);
    EXPECT_NEAR(rh.mean_age / fc.mean_age, 1.0, 0.1) << load;
    EXPECT_LT(rh.age_variance, 0.7 * fc.age_variance) << load;
    EXPECT_LT(rh.max_age, fc.max_age) << load;
    EXPECT_LE(rh.p99, fc.p99) << load;
    EXPECT_LT(rh.traversal_probes, fc.traversal_probes) << "FCFS cannot stop a traversal early";
  }
}

// Maximum age at fixed load 0.8 over tables of 2^10 to 2^20 slots: a least
// squares fit against ln N has a positive slope and explains most of the
// variation (R^2 > 0.8), as Robin Hood's O(log N) bound predicts.
TEST(Statistics, MaximumAgeGrowsLikeLogN) {
  std::vector<double> xs, ys;
  for (std::uint32_t side = 32; side <= 1024; side *= 2) {
    ExperimentConfig c;
    c.screen = {side, side};
    c.loads = {0.8};
    c.trials = side <= 128 ? 32 : side <= 256 ? 8 : 3;
    c.seed = 5;
    const auto rows = run_age_experiment(c);
    xs.push_back(std::log(static_cast<double>(side) * side));
    ys.push_back(rows[0].mean_max_age);
    std::printf("N = %u^2: mean max age %.2f +- %.2f\n", side, rows[0].mean_max_age, rows[0].mean_max_age_ci95);
  }
  const double n = static_cast<double>(xs.size());
  const double mx = std::accumulate(xs.begin(), xs.end(), 0.0) / n, my = std::accumulate(ys.begin(), ys.end(), 0.0) / n;
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) * (xs[i] - mx);
    syy += (ys[i] - my) * (ys[i] - my);
  }
  const double slope = sxy / sxx, r2 = sxy * sxy / (sxx * syy);
  EXPECT_GT(slope, 0.2);
  EXPECT_GT(r2, 0.8) << "slope " << slope;
}

// Traversal reads every age up to its block's max age: with B = 1 nothing is
// wasted; larger blocks waste more probes per pixel.
TEST(Statistics, WastedTraversalProbesGrowWithTheMaxAgeBlock) {
  std::vector<double> wasted;
  for (std::uint32_t block : {1u, 2u, 4u, 8u, 16u, 32u}) {
    ExperimentConfig c;
    c.screen = {256, 256};
    c.loads = {0.8};
    c.trials = 3;
    c.block = block;
    c.stream.kind = StreamKind::Coherent;
    const auto rows = run_age_experiment(c);
    wasted.push_back(rows[0].wasted_traversal_probes);
  }
  EXPECT_EQ(wasted[0], 0.0);
  for (std::size_t i = 1; i < wasted.size(); ++i) EXPECT_GT(wasted[i], wasted[i - 1]) << "block " << (1u << i);
}

}  // namespace
}  // namespace habuffer
