#include "habuffer/age_experiment.h"

#include "named_list.h"
#include "habuffer/memory_budget.h"
#include "habuffer/number_text.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "habuffer/record_layout.h"

namespace habuffer {
namespace {


// The rank bound of one stream: mean over distinct records of their rank in
// their pixel's list (records are distinct by pixel and depth code).
double rank_bound(const std::vector<Fragment>& frags, const RecordLayout& layout) {
  std::set<std::pair<std::uint64_t, std::uint32_t>> distinct;
  for (const Fragment& f : frags)
    if (RecordLayout::depth_valid(f.depth))
      distinct.insert({f.x + (std::uint64_t{f.y} << 32), layout.depth_code(f.depth)});
  std::map<std::uint64_t, std::uint64_t> per_pixel;
  for (const auto& d : distinct) ++per_pixel[d.first];
  double ranks = 0.0;
  for (const auto& [p, k] : per_pixel) ranks += static_cast<double>(k) * static_cast<double>(k + 1) / 2.0;
  return distinct.empty() ? 0.0 : ranks / static_cast<double>(distinct.size());
}

std::uint32_t percentile(const std::vector<std::uint64_t>& hist, double q) {
  std::uint64_t total = 0;
  for (auto n : hist) total += n;
  if (total == 0) return 0;
  const auto target = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::uint32_t a = 0; a < hist.size(); ++a) {
    seen += hist[a];
    if (seen >= std::max<std::uint64_t>(target, 1)) return a;
  }
  return static_cast<std::uint32_t>(hist.size() - 1);
}

}  // namespace

std::string Variant::name() const {
  return std::string(probing == Probing::Coherent ? "coherent" : "independent") + "/" +
         (policy == Policy::RobinHood ? "robinhood" : "fcfs") + "/" + to_string(offsets);
}

double Moments::ci95() const {
  return n > 1 ? student_t95(static_cast<std::uint32_t>(n) - 1) * std::sqrt(variance() / n) : 0.0;
}

double student_t95(std::uint32_t df) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                 2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                 2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (df == 0) return INFINITY;
  if (df <= 30) return table[df - 1];
  return 1.960 + 2.4 / static_cast<double>(df);  // within 0.002 of the exact quantile beyond 30
}

namespace {

// One variant's measurements at one load, summed over its trials.
struct VariantAccumulator {
  Moments age, excess, stored_load, max_age;
  std::vector<std::uint64_t> hist;
  std::uint64_t calls = 0, probes = 0, traversal = 0, wasted = 0, pixels = 0, failures = 0;
  std::uint32_t max_probes = 0;
  double bound = 0.0;

  // One trial's totals; `bound` is its stream's rank bound.
  void add_trial(const SimulatorTotals& tot, double trial_bound, std::uint32_t trials, Extent table) {
    std::uint64_t stored = 0, weighted = 0;
    std::uint32_t trial_max = 0;
    for (std::uint32_t g = 1; g < tot.age_histogram.size(); ++g) {
      stored += tot.age_histogram[g];
      weighted += std::uint64_t{g} * tot.age_histogram[g];
      if (tot.age_histogram[g] != 0) trial_max = g;
    }
    const double mean = stored ? static_cast<double>(weighted) / static_cast<double>(stored) : 0.0;
    age.add(mean);
    max_age.add(trial_max);
    excess.add(mean - trial_bound);
    bound += trial_bound / trials;
    stored_load.add(static_cast<double>(stored) / static_cast<double>(table.area()));
    if (hist.size() < tot.age_histogram.size()) hist.resize(tot.age_histogram.size(), 0);
    for (std::size_t g = 0; g < tot.age_histogram.size(); ++g) hist[g] += tot.age_histogram[g];
    calls += tot.counters.fragments - tot.counters.invalid;
    probes += tot.probes;
    max_probes = std::max(max_probes, tot.max_probes);
    traversal += tot.traversal_probes;
    wasted += tot.wasted_traversal_probes;
    pixels += tot.pixels;
    failures += tot.counters.failures();
  }

  // The pooled ages' variance (of every stored record over the trials).
  [[nodiscard]] double pooled_variance() const {
    double n = 0, s1 = 0, s2 = 0;
    for (std::size_t g = 1; g < hist.size(); ++g) {
      const double k = static_cast<double>(hist[g]);
      n += k;
      s1 += k * static_cast<double>(g);
      s2 += k * static_cast<double>(g) * static_cast<double>(g);
    }
    return n > 1 ? (s2 - s1 * s1 / n) / (n - 1) : 0.0;
  }

  [[nodiscard]] ExperimentRow row(const Variant& variant, double load, std::uint32_t trials) const {
    ExperimentRow r;
    r.variant = variant;
    r.load = load;
    r.stored_load = stored_load.mean();
    r.trials = trials;
    r.mean_age = age.mean();
    r.mean_age_ci95 = age.ci95();
    r.age_variance = pooled_variance();
    r.p50 = percentile(hist, 0.50);
    r.p90 = percentile(hist, 0.90);
    r.p99 = percentile(hist, 0.99);
    for (std::size_t g = 0; g < hist.size(); ++g)
      if (hist[g] != 0) r.max_age = static_cast<std::uint32_t>(g);
    r.mean_max_age = max_age.mean();
    r.mean_max_age_ci95 = max_age.ci95();
    r.rank_bound = bound;
    r.excess = excess.mean();
    r.excess_ci95 = excess.ci95();
    r.mean_probes = calls ? static_cast<double>(probes) / static_cast<double>(calls) : 0.0;
    r.max_probes = max_probes;
    r.traversal_probes = static_cast<double>(traversal) / static_cast<double>(pixels);
    r.wasted_traversal_probes = static_cast<double>(wasted) / static_cast<double>(pixels);
    r.failures = failures;
    return r;
  }
};


}  // namespace

void validate_experiment(const ExperimentConfig& c) {
  if (c.trials == 0) throw std::invalid_argument("trials: at least one trial is needed");
  if (c.screen.area() == 0) throw std::invalid_argument("screen " + c.screen.str() + " is empty");
  if (c.table != Extent{} && c.table.area() == 0)
    throw std::invalid_argument("table " + c.table.str() + " has a zero side (0x0 means the screen's size)");
  const Extent table = c.table == Extent{} ? c.screen : c.table;
  if (table.x < c.screen.x || table.y < c.screen.y)
    throw std::invalid_argument("table " + table.str() + " is smaller than screen " + c.screen.str());
  double max_load = 0.0;
  for (const double load : c.loads) {
    if (!(load > 0.0 && load <= kMaxExperimentLoad))
      throw std::invalid_argument("loads: " + shortest_text(load) + " is not a load in (0, 4]");
    if (load * static_cast<double>(table.area()) < 1.0)
      throw std::invalid_argument("loads: " + shortest_text(load) + " of table " + table.str() + " gives no fragment");
    max_load = std::max(max_load, load);
  }
  // The largest load's stream (16 bytes a fragment) and the table (8 bytes a slot).
  check_fits_in_memory("screen " + c.screen.str() + " (table " + table.str() + ")",
                       saturating_product(table.area(), 8 + static_cast<std::uint64_t>(std::ceil(16.0 * max_load))));
}

std::vector<ExperimentRow> run_age_experiment(const ExperimentConfig& c) {
  validate_experiment(c);
  const Extent table = c.table == Extent{} ? c.screen : c.table;
  const RecordLayout layout(Layout::L32, c.age_bits);
  std::vector<ExperimentRow> rows;
  const std::uint64_t total_trials = std::uint64_t{c.trials} * c.loads.size();
  std::uint64_t trials_done = 0;
  for (const double load : c.loads) {
    std::vector<VariantAccumulator> acc(c.variants.size());
    for (std::uint32_t t = 0; t < c.trials; ++t) {
      StreamOptions so = c.stream;
      so.count = static_cast<std::uint64_t>(std::llround(load * static_cast<double>(table.area())));
      so.seed = c.seed * 1000003 + t;
      const std::vector<Fragment> frags = make_stream(c.screen, so);
      const double bound = rank_bound(frags, layout);
      for (std::size_t v = 0; v < c.variants.size(); ++v) {
        SimulatorConfig sc{c.screen, table, c.age_bits, c.block, c.variants[v].probing, c.variants[v].policy,
                           so.seed * 31 + 7, c.variants[v].offsets};
        ProbeSimulator sim(sc);
        sim.insert(frags);
        acc[v].add_trial(sim.totals(), bound, c.trials, table);
      }
      if (c.on_progress) c.on_progress(++trials_done, total_trials);
    }
    for (std::size_t v = 0; v < c.variants.size(); ++v) rows.push_back(acc[v].row(c.variants[v], load, c.trials));
  }
  return rows;
}

double mean_ci95(std::span<const double> samples) {
  const auto n = static_cast<double>(samples.size());
  if (samples.size() < 2) return 0.0;
  double mean = 0.0, var = 0.0;
  for (const double a : samples) mean += a / n;
  for (const double a : samples) var += (a - mean) * (a - mean) / (n - 1.0);
  return student_t95(static_cast<std::uint32_t>(samples.size() - 1)) * std::sqrt(var / n);
}

std::vector<Probing> parse_probings(const std::vector<std::string>& names) {
  static constexpr std::pair<std::string_view, Probing> kNames[] = {{"coherent", Probing::Coherent},
                                                                    {"independent", Probing::Independent}};
  return detail::named_list<Probing>(names, kNames);
}

std::vector<Policy> parse_policies(const std::vector<std::string>& names) {
  static constexpr std::pair<std::string_view, Policy> kNames[] = {{"robinhood", Policy::RobinHood},
                                                                   {"fcfs", Policy::Fcfs}};
  return detail::named_list<Policy>(names, kNames);
}

std::vector<OffsetGenerator> parse_offset_generators(const std::vector<std::string>& names) {
  static constexpr std::pair<std::string_view, OffsetGenerator> kNames[] = {{"random", OffsetGenerator::Random},
                                                                            {"farthest", OffsetGenerator::Farthest}};
  return detail::named_list<OffsetGenerator>(names, kNames);
}

std::vector<Variant> variant_grid(const std::vector<Probing>& probings, const std::vector<Policy>& policies,
                                  const std::vector<OffsetGenerator>& offsets) {
  std::vector<Variant> out;
  for (const Probing pr : probings)
    for (const Policy po : policies)
      for (const OffsetGenerator of : offsets)
        if (pr == Probing::Coherent || of == offsets.front()) out.push_back({pr, po, of});
  return out;
}

StreamOptions experiment_stream(StreamKind kind, double spread, std::uint32_t age_bits) {
  StreamOptions s;
  s.kind = kind;
  s.spread = spread;
  s.hot_depth = (1u << age_bits) - 1;
  return s;
}

}  // namespace habuffer
