// The research harness (harness/): sweep, bench, figures, frontier and plan
// on tiny scenes. Structure and invariants of their tables, and the plan's
// predictions against measured renders.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/harness/bench.h"
#include "habuffer/harness/floors.h"
#include "habuffer/harness/figures.h"
#include "habuffer/harness/frontier.h"
#include "habuffer/harness/plan.h"
#include "habuffer/harness/shadow_frontier.h"
#include "habuffer/harness/sweep.h"
#include "habuffer/harness/technique_spec.h"

namespace habuffer::harness {
namespace {

using test::gl_context;

double num(const ResultRow& r, const std::string& c) { return r.number(c); }

std::string text(const ResultRow& r, const std::string& c) {
  const Cell* cell = r.find(c);
  return cell && std::holds_alternative<std::string>(*cell) ? std::get<std::string>(*cell) : std::string();
}

// Every fragment is stored or counted once under one reason.
void expect_accounting_identity(const ResultRow& r) {
  const double accounted = num(r, "stored") + num(r, "invalid") + num(r, "duplicates") + num(r, "culled") +
                           num(r, "saturated_rejected") + num(r, "blended") + num(r, "failures");
  EXPECT_EQ(num(r, "fragments"), accounted) << text(r, "technique");
  EXPECT_EQ(num(r, "failures"), num(r, "failed_age") + num(r, "failed_iter") + num(r, "dropped_pool") +
                                    num(r, "dropped_layers") + num(r, "occupancy_rejected"));
}

SweepSettings small_sweep(RenderPath path) {
  SweepSettings s;
  s.path = path;
  s.loads = {0.3, 0.6, 0.9};
  s.repeats = 3;
  s.threads = 2;
  return s;
}

TEST(Harness, SweepGivesOneRowPerLoadInOrderWithTheAccountingIdentityAndAgesGrowingWithLoad) {
  gl_context();
  const Workload w(parse_workload_spec("quads:count=24"), {48, 40});
  for (const RenderPath path : {RenderPath::Cpu, RenderPath::Gl}) {
    const ResultTable t = run_sweep(w, small_sweep(path));
    ASSERT_EQ(t.rows.size(), 3u);
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
      const ResultRow& r = t.rows[i];
      EXPECT_DOUBLE_EQ(num(r, "load"), small_sweep(path).loads[i]);
      EXPECT_NEAR(num(r, "measured_load"), num(r, "load"), 0.05);  // table sides rounded up
      expect_accounting_identity(r);
      EXPECT_EQ(num(r, "failures"), 0.0);
      EXPECT_GT(num(r, "mfrag_per_s"), 0.0);
      EXPECT_LE(num(r, "mfrag_per_s_min"), num(r, "mfrag_per_s"));
      EXPECT_GE(num(r, "mfrag_per_s_max"), num(r, "mfrag_per_s"));
      EXPECT_GE(num(r, "probes_per_fragment"), 1.0);
      EXPECT_LE(num(r, "p99_age"), num(r, "max_age"));
      const auto& h = std::get<std::vector<std::uint64_t>>(*r.find("age_histogram"));
      EXPECT_EQ(static_cast<double>(std::accumulate(h.begin(), h.end(), std::uint64_t{0})), num(r, "stored"));
      if (path == RenderPath::Gl) {
        EXPECT_GE(num(r, "slot_writes_per_fragment"), 1.0);
      }
      if (i > 0) {
        // Mean age does not fall with load beyond the two 95% intervals (about 99.7% jointly).
        const ResultRow& p = t.rows[i - 1];
        EXPECT_GE(num(r, "mean_age") + num(r, "mean_age_ci95") + num(p, "mean_age_ci95"), num(p, "mean_age"));
        EXPECT_LE(num(r, "memory_bytes"), num(p, "memory_bytes"));
      }
    }
  }
}

// Issue 36: the sweep compares techniques by their cost to sorted lists. The
// lists' separate sort pass (GPU path) is in sorted_ms; the CPU containers
// and the HA-buffer sort in their gather, which is then the whole cost.
TEST(Harness, SweepCountsASeparateSortPassInTheThroughputToSortedLists) {
  gl_context();
  const Workload w(parse_workload_spec("quads:count=24"), {48, 40});
  for (const char* technique : {"lists", "ha"})
    for (const RenderPath path : {RenderPath::Cpu, RenderPath::Gl}) {
      SweepSettings s = small_sweep(path);
      s.technique = parse_technique_spec(technique);
      s.repeats = 1;
      for (const ResultRow& r : run_sweep(w, s).rows) {
        const std::string where = std::string(technique) + (path == RenderPath::Gl ? " gl" : " cpu");
        EXPECT_DOUBLE_EQ(num(r, "sorted_ms"), num(r, "gather_ms") + num(r, "sort_ms")) << where;
        if (path == RenderPath::Gl && std::string(technique) == "lists") {
          EXPECT_GT(num(r, "sort_ms"), 0.0) << where;
          EXPECT_LT(num(r, "sorted_mfrag_per_s"), num(r, "mfrag_per_s")) << where;
        } else {
          EXPECT_EQ(num(r, "sort_ms"), 0.0) << where;
          EXPECT_DOUBLE_EQ(num(r, "sorted_mfrag_per_s"), num(r, "mfrag_per_s")) << where;
        }
      }
    }
}

TEST(Harness, SweepIsReproducibleFromItsSeedAndFreshOffsetsChangeTheAges) {
  gl_context();
  const Workload w(parse_workload_spec("quads:count=24"), {48, 40});
  SweepSettings s = small_sweep(RenderPath::Cpu);
  s.repeats = 1;
  s.loads = {0.9};
  const ResultTable a = run_sweep(w, s), b = run_sweep(w, s);
  s.seed = 7;
  const ResultTable c = run_sweep(w, s);
  const auto hist = [](const ResultTable& t) { return std::get<std::vector<std::uint64_t>>(*t.rows[0].find("age_histogram")); };
  EXPECT_EQ(hist(a), hist(b));
  EXPECT_NE(hist(a), hist(c));
}

TEST(Harness, SweepRefusesLoadsOutOfOrderAndLoadsNoTableCanGive) {
  gl_context();
  SweepSettings s = small_sweep(RenderPath::Cpu);
  s.loads = {0.6, 0.3};
  EXPECT_THROW(validate_sweep(s), std::invalid_argument);
  s.loads = {0.5};
  s.technique = parse_technique_spec("wboit");
  EXPECT_THROW(validate_sweep(s), std::invalid_argument);
  // 4 quads on 48x40 cover under a third of the screen once: no table at load 0.9 can be that small.
  const Workload w(parse_workload_spec("quads:count=4"), {48, 40});
  s = small_sweep(RenderPath::Cpu);
  try {
    (void)run_sweep(w, s);
    ADD_FAILURE() << "a load below the screen's slots was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("geometry rule"), std::string::npos) << e.what();
  }
}

TEST(Harness, BenchGivesEveryCombinationWithFloorsAndTheErrorOfEachTechnique) {
  gl_context();
  BenchSettings s;
  s.path = RenderPath::Cpu;
  s.scenes = {parse_workload_spec("quads:count=12"), parse_workload_spec("planes:order=front:count=6")};
  for (const char* t : {"ha", "lists", "kbuffer:k=1", "blend"}) s.techniques.push_back(parse_technique_spec(t));
  s.sizes = {{32, 24}, {40, 40}};
  s.repeats = 2;
  const ResultTable t = run_bench(s);
  ASSERT_EQ(t.rows.size(), 2u * 2u * 4u);
  for (const ResultRow& r : t.rows) {
    expect_accounting_identity(r);
    EXPECT_GT(num(r, "atomic_floor_ms"), 0.0);
    EXPECT_GT(num(r, "blend_floor_ms"), 0.0);
    EXPECT_GT(num(r, "exact_floor_ms"), 0.0);
    EXPECT_DOUBLE_EQ(num(r, "total_vs_exact_floor"), num(r, "total_ms") / num(r, "exact_floor_ms"));
    EXPECT_GT(num(r, "memory_bytes"), 0.0);
    EXPECT_DOUBLE_EQ(num(r, "total_ms"), num(r, "total_ms"));
    const std::string tech = text(r, "technique");
    if (tech == "ha" || tech == "lists") {  // float vs double compositing
      EXPECT_GT(num(r, "psnr"), 60.0) << tech;
    }
    if (tech == "kbuffer:k=1") {  // the nearest layer alone of overlapping quads
      EXPECT_LT(num(r, "psnr"), 40.0);
    }
    if (tech == "blend") {
      EXPECT_EQ(num(r, "blended"), num(r, "fragments"));
    }
  }
  s.path = RenderPath::Gl;
  EXPECT_NO_THROW(validate_bench(s));  // every technique has its GL form
}

// Issue 37: samples per pixel as a workload dimension ("quads:samples=4"):
// the capture and reference are per sample, every list technique keeps the
// masks (exact ones equal to one another and near the per-sample reference),
// and a technique without lists or a sample count outside 1, 2, 4, 8 is refused.
TEST(Harness, AMultisampledSceneWordRunsEveryListTechniqueWithMasksAgainstThePerSampleReference) {
  gl_context();
  EXPECT_EQ(parse_workload_spec("quads:count=6:samples=4").samples, 4u);
  EXPECT_EQ(parse_workload_spec("quads:count=6").samples, 1u);
  EXPECT_THROW((void)parse_workload_spec("quads:samples=3"), std::invalid_argument);
  BenchSettings s;
  s.path = RenderPath::Cpu;
  s.scenes = {parse_workload_spec("quads:count=12"), parse_workload_spec("quads:count=12:samples=4")};
  for (const char* t : {"ha", "lists", "sorted-lists"}) s.techniques.push_back(parse_technique_spec(t));
  s.sizes = {{32, 24}};
  s.repeats = 1;
  s.floors = false;
  const ResultTable t = run_bench(s);
  ASSERT_EQ(t.rows.size(), 6u);
  double one = 0.0, four = 0.0;
  for (const ResultRow& r : t.rows) {
    expect_accounting_identity(r);
    EXPECT_GT(num(r, "psnr"), 60.0) << text(r, "technique") << " " << text(r, "scene");
    (text(r, "scene") == "quads:count=12" ? one : four) = num(r, "fragments");
  }
  EXPECT_GT(four, one) << "the edges of a multisampled quad add the fragments of partly covered pixels";
  // The blended baselines keep their rows on the scene of one sample and
  // have none on the multisampled one (a warning names them).
  s.techniques.push_back(parse_technique_spec("wboit"));
  std::vector<std::string> warnings;
  s.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ResultTable with_wboit = run_bench(s);
  EXPECT_EQ(with_wboit.rows.size(), 7u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("wboit have no rows for the multisampled scenes 'quads:count=12:samples=4'"),
            std::string::npos) << warnings[0];
  s.techniques = {parse_technique_spec("wboit")};
  try {
    validate_bench(s);
    ADD_FAILURE() << "a multisampled scene with no list technique was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("none of the techniques keeps coverage masks"), std::string::npos) << e.what();
  }
}

// The exact floor (issue 36) does an exact technique's whole work: its
// image is every exact technique's, bit for bit, duplicates and invalid
// depths included, at any thread count; it refuses a wrong background count
// and a fragment off the screen.
TEST(Harness, TheExactFloorsImageIsTheHaBuffersBitForBit) {
  const Extent screen{37, 23};
  auto f = test::stream(screen, StreamKind::Random, 4000, 9);
  for (std::size_t i = 0; i < 300; ++i) f.push_back(f[i * 7]);  // duplicates
  f[5].depth = std::numeric_limits<float>::quiet_NaN();
  f[6].depth = 2.0f;
  std::vector<glm::vec3> backgrounds(screen.area());
  for (std::size_t i = 0; i < backgrounds.size(); ++i) backgrounds[i] = glm::vec3(0.1f * static_cast<float>(i % 10), 0.5f, 1.0f);
  HaBuffer ha = test::make_buffer(test::config(screen, {111, 69}));  // load about 0.55
  ASSERT_EQ(ha.insert(f).failures(), 0u);
  const auto want = ha.composite_image(backgrounds, 1);
  ExactFloor floor;
  for (std::uint32_t threads : {1u, 3u}) EXPECT_TRUE(test::same_bits(floor.image(f, screen, backgrounds, threads), want));
  EXPECT_THROW((void)floor.image(f, screen, std::span(backgrounds).first(10), 1), std::invalid_argument);
  f[9].x = screen.x;
  EXPECT_THROW((void)floor.image(f, screen, backgrounds, 1), std::out_of_range);
}

// Issue 36: bench --model gpu replays each row's frame through the technique's
// traced kernel: the model's columns on the rows it covers, none on the others,
// and the counts no order changes (the lists: a node counter add, a head
// exchange and a tally per fragment, two chain links per warp).
TEST(Harness, BenchWithTheGpuModelAddsItsColumnsToTheTechniquesItCovers) {
  gl_context();
  BenchSettings s;
  s.path = RenderPath::Cpu;
  s.scenes = {parse_workload_spec("planes:order=front:count=4")};
  for (const char* t : {"ha", "lists", "arrays:k=4", "blend"}) s.techniques.push_back(parse_technique_spec(t));
  s.sizes = {{32, 24}};
  s.repeats = 1;
  s.floors = false;
  s.model_gpu = true;
  const ResultTable t = run_bench(s);
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(t.notes.count("model"), 1u);
  for (const ResultRow& r : t.rows) {
    const std::string tech = text(r, "technique");
    if (tech == "blend") {
      EXPECT_EQ(r.find("model_gather_sectors"), nullptr);
      continue;
    }
    const double fragments = num(r, "fragments"), warps = std::ceil(fragments / 32.0);
    ASSERT_GT(fragments, 0.0);
    EXPECT_GT(num(r, "model_gather_sectors"), 0.0) << tech;
    EXPECT_GT(num(r, "model_resolve_instructions"), 0.0) << tech;
    EXPECT_GT(num(r, "model_total_ms"), num(r, "model_gather_ms")) << tech;
    if (tech == "lists") {
      EXPECT_EQ(num(r, "model_gather_atomics"), 3.0 * fragments);
      EXPECT_EQ(num(r, "model_gather_chain"), 2.0 * warps);
      EXPECT_GT(num(r, "model_sort_instructions"), 0.0);
    }
    if (tech == "arrays:k=4") {
      EXPECT_EQ(num(r, "model_gather_atomics"), 2.0 * fragments);
    }
    if (tech == "ha") {
      EXPECT_EQ(num(r, "model_sort_instructions"), 0.0);
    }
  }
}

// Issue 34: a scene with no transparent fragment (opaque planes) gave a row
// of 0 fragments timing an empty pass without a word: bench warns, one line
// per scene naming it and its sizes, kept in the notes; sweep refuses it.
TEST(Harness, AScenePuttingNoTransparentFragmentIsWarnedAboutByBenchAndRefusedBySweep) {
  gl_context();
  BenchSettings s;
  s.path = RenderPath::Cpu;
  s.scenes = {parse_workload_spec("planes:opacity=1:count=2"), parse_workload_spec("quads:count=2")};
  s.techniques = {parse_technique_spec("ha")};
  s.sizes = {{16, 16}, {24, 16}};
  s.repeats = 1;
  s.floors = false;
  std::vector<std::string> warnings;
  s.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ResultTable t = run_bench(s);
  ASSERT_EQ(warnings.size(), 1u) << "one line per scene, whatever its sizes";
  EXPECT_NE(warnings[0].find("scene 'planes:opacity=1:count=2' puts no transparent fragment on the screen at 16x16, 24x16"),
            std::string::npos)
      << warnings[0];
  EXPECT_EQ(warnings[0].find('\n'), std::string::npos);
  ASSERT_EQ(t.notes.count("warnings"), 1u);
  EXPECT_NE(t.notes.at("warnings").find("planes:opacity=1"), std::string::npos);
  const Workload opaque(parse_workload_spec("planes:opacity=1:count=2"), {16, 16});
  try {
    (void)run_sweep(opaque, small_sweep(RenderPath::Cpu));
    ADD_FAILURE() << "sweep ran a scene without transparent fragments";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("puts no transparent fragment on the screen at 16x16"), std::string::npos)
        << e.what();
  }
}

// Issue 34: sweep's counter columns sum the repeats' runs; the table says so.
TEST(Harness, SweepSaysItsCounterColumnsSumTheRepeats) {
  gl_context();
  const Workload w(parse_workload_spec("quads:count=24"), {48, 40});
  SweepSettings s = small_sweep(RenderPath::Cpu);
  s.loads = {0.9};
  s.repeats = 3;
  const ResultTable t = run_sweep(w, s);
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(num(t.rows[0], "repeats"), 3.0);
  EXPECT_EQ(num(t.rows[0], "fragments"), 3.0 * std::stod(t.notes.at("fragments")));
  ASSERT_EQ(t.notes.count("counters"), 1u);
  EXPECT_NE(t.notes.at("counters").find("sums over the row's repeats runs"), std::string::npos) << t.notes.at("counters");
  ASSERT_EQ(t.notes.count("repeats"), 1u);
}

TEST(Harness, Fig10SaturationRejectsFrontToBackPlanesOnBothPaths) {
  gl_context();
  FigureSettings f;
  f.size = {32, 32};
  f.repeats = 1;
  // Submission order is the experiment: with two CPU threads the back half
  // of the planes was inserted beside the front half, and in 2 to 4 runs of
  // 10 nothing was culled before the back planes were stored (no saturation).
  f.threads = 1;
  for (const RenderPath path : {RenderPath::Cpu, RenderPath::Gl}) {
    f.path = path;
    BenchSettings b = fig10_bench_settings(12, f);
    const ResultTable t = run_bench(b);
    ASSERT_EQ(t.rows.size(), 12u);
    for (const ResultRow& r : t.rows) {
      expect_accounting_identity(r);
      const bool sat = text(r, "technique").find(":sat") != std::string::npos;
      const bool front = text(r, "scene").find("front") != std::string::npos;
      if (sat && front && path == RenderPath::Cpu) {
        EXPECT_GT(num(r, "saturated_rejected"), 0.0) << text(r, "technique");
      }
      // A GPU runs the planes' fragment shaders concurrently, not in draw
      // order (an H100 once rejected none as saturated, culling instead):
      // early termination of either kind is what front to back guarantees there.
      if (sat && front && path == RenderPath::Gl) {
        EXPECT_GT(num(r, "saturated_rejected") + num(r, "culled"), 0.0) << text(r, "technique");
      }
      if (!sat) {
        EXPECT_EQ(num(r, "saturated_rejected"), 0.0);
      }
    }
  }
}

TEST(Harness, Fig2InsertsOpacityOneAndCullingStoresLessAsOpacityGrows) {
  gl_context();
  FigureSettings f;
  f.size = {40, 40};
  f.repeats = 1;
  f.path = RenderPath::Cpu;
  const ResultTable t = run_fig2(parse_workload_spec("hairball:count=80"), {0.25f, 1.0f}, f);
  ASSERT_EQ(t.rows.size(), 4u);
  for (const ResultRow& r : t.rows) EXPECT_GT(num(r, "fragments"), 0.0);  // opacity 1 reached the buffer
  EXPECT_EQ(num(t.rows[2], "stored"), num(t.rows[2], "fragments"));      // opacity 1, no cull: all stored
  EXPECT_LT(num(t.rows[3], "stored"), num(t.rows[1], "stored"));         // cull stores less at opacity 1
  // The shadow columns: the light buffer built once, its fragments beside the view's, both frame times.
  for (const ResultRow& r : t.rows) {
    EXPECT_EQ(num(r, "light_builds"), 1.0);
    EXPECT_GT(num(r, "light_fragments"), 0.0);
    EXPECT_EQ(num(r, "fragments_with_shadows"), num(r, "fragments") + num(r, "light_fragments"));
    EXPECT_GT(num(r, "fps"), 0.0);
    EXPECT_GT(num(r, "fps_shadows"), 0.0);
  }
  EXPECT_LT(num(t.rows[3], "light_stored"), num(t.rows[2], "light_stored"));  // the light buffer culled too
}

// The shadow frontier: every light buffer scored at the same receivers; the
// HA-buffer built on the GPU and on the CPU from its captured stream give
// the same T everywhere; the exact one meets the goal outside the bands and
// beats the opacity maps, which smear each slice.
TEST(Harness, TheShadowFrontierScoresEveryLightBufferAtTheSameReceivers) {
  gl_context();
  ShadowFrontierSettings f;
  f.size = {64, 64};
  f.light_size = {128, 128};
  f.repeats = 1;
  const ResultTable t = run_shadow_frontier(parse_workload_spec("engine"), f);
  ASSERT_EQ(t.rows.size(), 8u);
  for (const ResultRow& r : t.rows) EXPECT_EQ(num(r, "receivers"), num(t.rows[0], "receivers"));
  EXPECT_EQ(text(t.rows[0], "build_path"), "gl");
  EXPECT_EQ(text(t.rows[1], "parameter"), "exact");
  EXPECT_EQ(num(t.rows[0], "rmse"), num(t.rows[1], "rmse"));
  EXPECT_EQ(num(t.rows[0], "stored"), num(t.rows[1], "stored"));
  EXPECT_GE(num(t.rows[1], "within_fraction"), 0.999);
  EXPECT_LE(num(t.rows[1], "rmse"), num(t.rows[3], "rmse"));  // culling at 0.9 loses accuracy
  EXPECT_EQ(num(t.rows[4], "memory_bytes"), 4.0 * 128 * 128 * 8);  // k-buffer k 4: 4 records per pixel
  EXPECT_EQ(num(t.rows[6], "memory_bytes"), 17.0 * 128 * 128 * 4);  // 16 slices: 17 planes of floats
  EXPECT_LT(num(t.rows[1], "rmse_outside_band"), num(t.rows[7], "rmse_outside_band"));
  EXPECT_THROW((void)run_shadow_frontier(parse_workload_spec("f.csv"), f), std::invalid_argument);
}

TEST(Harness, Fig8KeepsTheTableAndTheFragmentCountWhileTheQuadsStack) {
  gl_context();
  FigureSettings f;
  f.size = {32, 32};
  f.path = RenderPath::Cpu;
  const ResultTable t = run_fig8(parse_workload_spec("quads:count=32"), 3, 0.64, f);
  ASSERT_EQ(t.rows.size(), 6u);
  for (const ResultRow& r : t.rows) {
    EXPECT_EQ(text(r, "table"), text(t.rows[0], "table"));
    EXPECT_EQ(num(r, "fragments"), num(t.rows[0], "fragments"));
  }
  EXPECT_DOUBLE_EQ(num(t.rows.back(), "spread"), 0.0);
  EXPECT_GT(num(t.rows[4], "max_age"), num(t.rows[0], "max_age"));  // stacked: every pixel deep
}

TEST(Harness, TheMemoryTableMatchesThePapersPublishedValuesAndTheContainers) {
  const ResultTable t = run_memory_table({1024, 1024}, {850000, 1500000}, {0.8, 0.5}, true);
  int published = 0;
  for (const ResultRow& r : t.rows) {
    if (r.find("paper_table_mib")) {
      ++published;
      EXPECT_NEAR(num(r, "paper_formula_mib"), num(r, "paper_table_mib"), 0.06) << text(r, "technique");
    }
    if (r.find("allocated_mib")) {
      EXPECT_DOUBLE_EQ(num(r, "allocated_mib"), num(r, "model_mib")) << text(r, "technique");
    }
  }
  EXPECT_EQ(published, 2 * 3);  // lists, ha 80% and ha 50% at both counts
}

TEST(Harness, ParetoMarksOnlyUndominatedRowsPerScene) {
  ResultTable t;
  const auto row = [&](const char* scene, const char* tech, double ms, double mem, double psnr) {
    ResultRow r;
    r.set("scene", scene).set("size", "8x8").set("path", "cpu").set("technique", tech).set("total_ms", ms)
        .set("memory_bytes", mem).set("bytes_per_fragment", mem / 10.0).set("psnr", psnr);
    t.rows.push_back(r);
  };
  row("a", "fast-bad", 1.0, 100.0, 20.0);
  row("a", "slow-good", 5.0, 50.0, INFINITY);
  row("a", "dominated", 6.0, 200.0, 19.0);
  row("b", "alone", 9.0, 9.0, 10.0);
  mark_pareto(t);
  const auto mark = [&](std::size_t i, const char* c) { return std::get<bool>(*t.rows[i].find(c)); };
  EXPECT_TRUE(mark(0, "pareto_time"));
  EXPECT_TRUE(mark(1, "pareto_time"));
  EXPECT_FALSE(mark(2, "pareto_time"));
  EXPECT_FALSE(mark(0, "pareto_memory"));  // slow-good uses less memory and is exact
  EXPECT_TRUE(mark(1, "pareto_memory"));
  EXPECT_TRUE(mark(3, "pareto_time"));
  const ResultTable picks = frontier_picks(t, {15.0, 30.0});
  EXPECT_EQ(text(picks.rows[0], "technique"), "fast-bad");
  EXPECT_EQ(text(picks.rows[1], "technique"), "slow-good");
}

TEST(Harness, TechniqueWordsReadBackToTheirLabelsAndBadKnobsAreRefusedByName) {
  for (const char* w : {"ha", "ha:cull=0.99:sat", "ha:load=0.8:age=6", "kbuffer:k=8:occ:words=2", "lists:load=0.5",
                        "sorted-lists:cull=0.9", "arrays:k=16", "wboit", "blend"})
    EXPECT_EQ(parse_technique_spec(w).label(), w);
  for (const char* bad : {"hb", "ha:k=4", "kbuffer:cull=0.9", "ha:sat", "ha:load=1.5", "arrays:k=0", "ha:cull=x",
                          "lists:occ", "kbuffer:words=2"})
    EXPECT_THROW((void)parse_technique_spec(bad), std::invalid_argument) << bad;
  EXPECT_THROW((void)parse_workload_spec("planes:order=up"), std::invalid_argument);
  EXPECT_THROW((void)parse_workload_spec("planes:depth=3"), std::invalid_argument);
}

TEST(Harness, EqualPointsAreBothOnTheParetoFrontAndAStrictlyBetterOneDropsThem) {
  ResultTable t;
  const auto row = [&](const char* tech, double ms, double mem, double psnr) {
    ResultRow r;
    r.set("scene", "a").set("size", "8x8").set("path", "cpu").set("technique", tech).set("total_ms", ms)
        .set("memory_bytes", mem).set("psnr", psnr);
    t.rows.push_back(r);
  };
  row("twin-1", 2.0, 64.0, 40.0);
  row("twin-2", 2.0, 64.0, 40.0);
  row("slower-same-psnr", 2.5, 64.0, 40.0);
  row("same-time-worse", 2.0, 64.0, 39.0);
  mark_pareto(t);
  const auto mark = [&](std::size_t i, const char* c) { return std::get<bool>(*t.rows[i].find(c)); };
  EXPECT_TRUE(mark(0, "pareto_time")) << "a tie dominates nobody";
  EXPECT_TRUE(mark(1, "pareto_time"));
  EXPECT_TRUE(mark(0, "pareto_memory"));
  EXPECT_TRUE(mark(1, "pareto_memory"));
  EXPECT_FALSE(mark(2, "pareto_time")) << "as accurate, strictly slower";
  EXPECT_TRUE(mark(2, "pareto_memory")) << "as much memory and as accurate: a tie in memory";
  EXPECT_FALSE(mark(3, "pareto_time")) << "as fast, strictly less accurate";
}

// Issue 36: the frontier in time, memory and error at once. A row is on it
// when no other row is at least as good on all three and better on one.
ResultRow frontier_row(const char* tech, double ms, double bytes_per_fragment, double psnr) {
  ResultRow r;
  r.set("scene", "a").set("size", "8x8").set("path", "cpu").set("technique", tech).set("total_ms", ms)
      .set("memory_bytes", 100.0 * bytes_per_fragment).set("bytes_per_fragment", bytes_per_fragment).set("psnr", psnr);
  return r;
}

TEST(Harness, TheThreeAxisFrontKeepsARowThatEachTwoAxisFrontDropsAndDropsOnlyRowsDominatedOnAllThree) {
  ResultTable t;
  t.rows = {frontier_row("fast-big", 1.0, 16.0, INFINITY), frontier_row("slow-small", 5.0, 8.0, INFINITY),
            frontier_row("between", 3.0, 12.0, INFINITY), frontier_row("worse-everywhere", 6.0, 20.0, 30.0),
            frontier_row("slower-same-rest", 1.5, 16.0, INFINITY), frontier_row("cheap-lossy", 0.5, 2.0, 20.0)};
  mark_pareto(t);
  const auto mark = [&](std::size_t i, const char* c) { return std::get<bool>(*t.rows[i].find(c)); };
  EXPECT_TRUE(mark(0, "pareto_3d"));
  EXPECT_TRUE(mark(1, "pareto_3d"));
  EXPECT_FALSE(mark(2, "pareto_time")) << "fast-big is faster and as exact";
  EXPECT_FALSE(mark(2, "pareto_memory")) << "slow-small is smaller and as exact";
  EXPECT_TRUE(mark(2, "pareto_3d")) << "neither is both faster and smaller";
  EXPECT_FALSE(mark(3, "pareto_3d")) << "slower, larger and less accurate than fast-big";
  EXPECT_FALSE(mark(4, "pareto_3d")) << "equal to fast-big in memory and psnr, slower";
  EXPECT_TRUE(mark(5, "pareto_3d")) << "the fastest and smallest, however inaccurate";
  EXPECT_NE(t.notes.at("pareto").find("pareto_3d (total_ms, memory_bytes, psnr)"), std::string::npos);
}

TEST(Harness, RowsEqualOnAllThreeAxesStayOnTheThreeAxisFrontTogether) {
  ResultTable t;
  t.rows = {frontier_row("twin-1", 2.0, 8.0, 40.0), frontier_row("twin-2", 2.0, 8.0, 40.0),
            frontier_row("twin-but-worse", 2.0, 8.0, 39.0), frontier_row("other-scene", 9.0, 90.0, 1.0)};
  t.rows[3].set("scene", "b");
  mark_pareto(t);
  const auto mark = [&](std::size_t i) { return std::get<bool>(*t.rows[i].find("pareto_3d")); };
  EXPECT_TRUE(mark(0)) << "a tie dominates nobody";
  EXPECT_TRUE(mark(1));
  EXPECT_FALSE(mark(2));
  EXPECT_TRUE(mark(3)) << "alone in its scene";
}

TEST(Harness, PicksAreTheFastestRowMeetingEachTargetWithinEachMemoryBudgetOrNone) {
  ResultTable t;
  t.rows = {frontier_row("lists", 1.0, 17.0, INFINITY), frontier_row("ha:load=0.9", 2.0, 9.0, INFINITY),
            frontier_row("kbuffer:k=1", 0.5, 4.0, 25.0)};
  const ResultTable picks = frontier_picks(t, {20.0, 50.0}, {kNoMemoryBudget, 10.0, 3.0});
  ASSERT_EQ(picks.rows.size(), 6u);  // per target, per budget in the order given
  const auto pick = [&](std::size_t i) { return text(picks.rows[i], "technique"); };
  EXPECT_EQ(pick(0), "kbuffer:k=1");  // 20 dB, no budget
  EXPECT_EQ(pick(1), "kbuffer:k=1");  // 20 dB, 10 B
  EXPECT_EQ(pick(2), "none");         // 20 dB, 3 B: nothing is that small
  EXPECT_EQ(pick(3), "lists");        // exact, no budget: the fastest exact
  EXPECT_EQ(pick(4), "ha:load=0.9");  // exact within 10 B per fragment: lists do not fit
  EXPECT_EQ(pick(5), "none");
  EXPECT_EQ(num(picks.rows[4], "memory_budget"), 10.0);
  EXPECT_EQ(num(picks.rows[4], "bytes_per_fragment"), 9.0);
  EXPECT_TRUE(std::isinf(num(picks.rows[3], "memory_budget")));
  EXPECT_EQ(picks.rows[5].find("total_ms"), nullptr);
}

TEST(Harness, SceneWordsObeyRendersRulesForEveryKey) {
  const WorkloadSpec ok = parse_workload_spec("quads:count=8:seed=7:opacity=1:spread=0.5");
  EXPECT_EQ(ok.options.count, 8u);
  EXPECT_EQ(ok.options.seed, 7u);
  EXPECT_EQ(ok.options.spread, 0.5f);
  EXPECT_EQ(parse_workload_spec("planes:count=1048576:order=front").options.order, PlaneOrder::FrontToBack);
  EXPECT_EQ(parse_workload_spec("frags.csv").fragments, "frags.csv");
  const auto refusal = [](const std::string& w) {
    try {
      (void)parse_workload_spec(w);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::pair<const char*, const char*> refused[] = {
      {"quads:count=0", "outside 1..1048576"},
      {"planes:count=1048577", "outside 1..1048576"},
      {"planes:count=1000000000", "outside 1..1048576"},
      {"quads:opacity=0.00196", "above 1/510"},  // 1/510 = 0.0019608: rounds to alpha 0
      {"quads:opacity=1.5", "outside (0, 1]"},
      {"quads:spread=-0.1", "outside [0, 1]"},
      {"quads:order=front", "does not take order"},
      {"engine:count=3", "does not take count"},
      {"planes:seed=3", "does not take seed"},
      {"planes:spread=0.5", "does not take spread"},
      {"frags.csv:count=3", "a fragment file takes no options"},
      {"quads:count=3:count=4", "count given twice"},
      {"planes:", "empty option"},
      {"quads:count=1e3", "not a non-negative integer"},
      {"quads:opacity=1e-50", "outside float32's range"},
  };
  for (const auto& [word, why] : refused) {
    const std::string m = refusal(word);
    EXPECT_NE(m.find(why), std::string::npos) << word << ": " << m;
    EXPECT_NE(m.find(word), std::string::npos) << word << " is not named in: " << m;
  }
}

TEST(Harness, TechniqueWordsObeyTheOptionsRulesAndLoadsThatOverflowAreRefusedNamingTheLoad) {
  const std::pair<const char*, const char*> refused[] = {
      {"ha:cull=1e-40", "smallest normal float32"},  // a subnormal: a GPU may flush it to 0
      {"ha:cull=0", "threshold must be in (0, 1]"},
      {"ha:cull=0.5:cull=0.6", "cull given twice"},
      {"ha:load=0.5:load=0.6", "load given twice"},
      {"ha:age=13", "outside 4..12"},
      {"ha:age=3", "outside 4..12"},
      {"arrays:k=65537", "outside 1..65536"},
      {"kbuffer:k=4:occ:words=33", "outside 1..32"},
      {"ha:load=0", "load must be in (0, 1]"},
  };
  for (const auto& [word, why] : refused) {
    try {
      (void)parse_technique_spec(word);
      ADD_FAILURE() << word << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << word << ": " << e.what();
    }
  }
  EXPECT_EQ(parse_technique_spec("ha:cull=1.17549435e-38").cull, std::numeric_limits<float>::min());
  for (const auto& size : {std::function<void()>([] { (void)table_for_load({16, 16}, 1024, 1e-300); }),
                           std::function<void()>([] { (void)capacity_for_load(1024, 1e-300); })}) {
    try {
      size();
      ADD_FAILURE() << "a load of 1e-300 was sized";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("load 1e-300"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("2^32"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(capacity_for_load(1024, 0.5), 2048u);
  EXPECT_EQ(table_for_load({16, 16}, 1024, 1.0), (Extent{32, 32}));
}

TEST(Harness, SweepRefusesASizeInTheTechniqueWordThatItWouldOverride) {
  SweepSettings s = small_sweep(RenderPath::Cpu);
  for (const char* w : {"ha:load=0.5", "arrays:k=4", "lists:load=0.9"}) {
    s.technique = parse_technique_spec(w);
    EXPECT_THROW(validate_sweep(s), std::invalid_argument) << w;
  }
  s.technique = parse_technique_spec("ha:cull=0.9");
  EXPECT_NO_THROW(validate_sweep(s));
}

TEST(Harness, FiguresRefuseScenesWhoseKnobTheyVaryAndTable1BoundsItsSizes) {
  EXPECT_THROW(check_fig2_scene(parse_workload_spec("f.csv")), std::invalid_argument);
  EXPECT_THROW(check_fig2_scene(parse_workload_spec("hairball:opacity=0.5")), std::invalid_argument);
  EXPECT_NO_THROW(check_fig2_scene(parse_workload_spec("hairball:count=10")));
  EXPECT_THROW(check_fig8_scene(parse_workload_spec("planes")), std::invalid_argument);
  EXPECT_THROW(check_fig8_scene(parse_workload_spec("quads:spread=0.5")), std::invalid_argument);
  EXPECT_NO_THROW(check_fig8_scene(parse_workload_spec("quads:count=8")));
  EXPECT_THROW(validate_memory_table({64, 64}, {1000}, {0.0}), std::invalid_argument);
  EXPECT_THROW(validate_memory_table({64, 64}, {1000}, {1.5}), std::invalid_argument);
  EXPECT_THROW(validate_memory_table({64, 64}, {0}, {0.5}), std::invalid_argument);
  EXPECT_THROW(validate_memory_table({64, 64}, {kMaxTableFragments + 1}, {0.5}), std::invalid_argument);
  EXPECT_THROW(validate_memory_table({64, 64}, {kMaxTableFragments}, {0.4}), std::invalid_argument);
  EXPECT_NO_THROW(validate_memory_table({64, 64}, {kMaxTableFragments}, {1.0}));
}

// A target PSNR is a finite number of dB above 0, refused before any work
// (habuffer plan --target-psnr, habuffer.plan(target_psnr=...)).
TEST(Harness, ThePlanRefusesATargetPsnrThatIsNotAFinitePositiveNumberOfDecibels) {
  const ExactCapture none{};  // no fragment: a target that passes reaches the capture's own refusal
  for (const double t : {-1.0, 0.0, -0.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    PlanSettings ps;
    ps.target_psnr = t;
    try {
      (void)plan_from_capture(none, {4, 4}, ps);
      ADD_FAILURE() << "target PSNR " << t << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("is not a finite PSNR above 0 dB"), std::string::npos) << e.what();
    }
  }
  PlanSettings ps;
  ps.target_psnr = 30.0;
  try {
    (void)plan_from_capture(none, {4, 4}, ps);
    ADD_FAILURE() << "a plan of no fragment accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no fragment"), std::string::npos) << e.what();
  }
}

// A capture made by hand: 4x4 pixels, three fragments each of distinct
// colours and depths, over a white background.
ExactCapture three_deep_capture() {
  ExactCapture c;
  const Extent screen{4, 4};
  c.pixel_fragments.assign(screen.area(), 3);
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      for (std::uint32_t i = 0; i < 3; ++i)
        c.stream.push_back(Fragment{x, y, 0.9f - 0.3f * static_cast<float>(i), 0x80000000u | (0xffu << (8 * i))});
  c.fragments = c.stream.size();
  c.backgrounds.assign(screen.area(), glm::vec3(1.0f));
  c.reference = reference_image(c.stream, screen, c.backgrounds);
  return c;
}

// Issue 36: `plan --memory-budget`: the least memory meeting the aim within
// the budget; below every such configuration, the most accurate within it;
// below every configuration, none.
TEST(Harness, ThePlanRecommendsWithinAMemoryBudgetAndTheMostAccurateThereWhenNoneIsLossless) {
  const ExactCapture c = three_deep_capture();
  PlanSettings ps;
  ps.loads = {0.5, 0.9};
  ps.trials = 1;
  const ResultTable unbudgeted = plan_from_capture(c, {4, 4}, ps);
  const std::string cheapest = unbudgeted.notes.at("recommendation");
  double cheapest_bytes = 0.0;
  for (const ResultRow& r : unbudgeted.rows)
    if (text(r, "technique") == cheapest) cheapest_bytes = num(r, "bytes_per_fragment");
  ASSERT_GT(cheapest_bytes, 0.0);

  ps.memory_budget = cheapest_bytes;
  const ResultTable fits = plan_from_capture(c, {4, 4}, ps);
  EXPECT_EQ(fits.notes.at("recommendation"), cheapest);
  EXPECT_NE(fits.notes.at("budget").find("the least memory meeting losslessness within it"), std::string::npos);

  ps.memory_budget = cheapest_bytes - 0.01;
  const ResultTable tight = plan_from_capture(c, {4, 4}, ps);
  EXPECT_NE(tight.notes.at("budget").find("no configuration meets losslessness within it"), std::string::npos);
  const ResultRow* chosen = nullptr;
  for (const ResultRow& r : tight.rows)
    if (std::get<bool>(*r.find("recommended"))) chosen = &r;
  ASSERT_NE(chosen, nullptr);
  EXPECT_TRUE(std::get<bool>(*chosen->find("within_budget")));
  EXPECT_FALSE(std::get<bool>(*chosen->find("lossless")));
  for (const ResultRow& r : tight.rows)
    if (std::get<bool>(*r.find("within_budget")) && r.find("predicted_psnr") && text(r, "technique").rfind("ha", 0) != 0) {
      EXPECT_GE(num(*chosen, "predicted_psnr"), num(r, "predicted_psnr")) << text(r, "technique");
    }

  ps.memory_budget = 0.0;
  EXPECT_EQ(plan_from_capture(c, {4, 4}, ps).notes.at("recommendation"), "none fits the memory budget");
  ps.memory_budget = -1.0;
  EXPECT_THROW((void)plan_from_capture(c, {4, 4}, ps), std::invalid_argument);
}

// The plan's predictions for engine at 256x256 against measured renders:
// memory exactly (the model is what the containers allocate), the
// HA-buffer's max age within 15% (its model inserts a synthetic stream with
// the same per-pixel counts under other offsets), the k-buffer's and the
// arrays' PSNR within 0.1 dB (the same fragments kept, float vs double).
TEST(Harness, ThePlanPredictsEnginesMemoryMaxAgeAndTruncationErrorWithinItsTolerance) {
  gl_context();
  const Workload w(parse_workload_spec("engine"), {256, 256});
  const ExactCapture capture = w.capture();
  PlanSettings ps;
  ps.loads = {0.5, 0.8};
  const ResultTable plan = plan_from_capture(capture, w.size(), ps);
  int checked = 0;
  for (const ResultRow& p : plan.rows) {
    const std::string tech = text(p, "technique");
    if (tech != "ha:load=0.5" && tech != "ha:load=0.8" && tech != "kbuffer:k=4" && tech != "arrays:k=4") continue;
    RenderSettings s;
    s.path = RenderPath::Cpu;
    s.threads = 1;  // fixed arrays keep the first K to arrive: stream order, as the plan assumes
    s.config.screen = w.size();
    parse_technique_spec(tech).apply(s, capture.fragments);
    const RenderResult r = w.render(s);
    EXPECT_EQ(num(p, "memory_bytes"), static_cast<double>(r.memory_model_bytes)) << tech;
    if (tech.rfind("ha", 0) == 0) {
      const double measured = r.frames[0].max_age;
      EXPECT_NEAR(num(p, "predicted_max_age"), measured, 0.15 * measured) << tech;
      EXPECT_EQ(r.frames[0].counters.failures(), 0u);
      EXPECT_EQ(num(p, "failure_risk"), 0.0);
    } else {
      EXPECT_NEAR(num(p, "predicted_psnr"), compare_pixels(r.image, capture.reference).psnr, 0.1) << tech;
      // The plan counts every fragment beyond K; the technique first merges identical records as duplicates.
      const Counters& c = r.frames[0].counters;
      EXPECT_GE(num(p, "predicted_failures"), static_cast<double>(c.failures())) << tech;
      EXPECT_LE(num(p, "predicted_failures"), static_cast<double>(c.failures() + c.duplicates)) << tech;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 4);
  EXPECT_NE(plan.notes.at("recommendation"), "none meets the target");
}

}  // namespace
}  // namespace habuffer::harness
