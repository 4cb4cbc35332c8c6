#include "habuffer/harness/plan.h"
#include "habuffer/technique_descriptor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "habuffer/harness/technique_spec.h"
#include "habuffer/memory_model.h"
#include "habuffer/number_text.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/probe_simulator.h"

namespace habuffer::harness {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Prediction {
  TechniqueSpec spec;
  std::uint64_t memory = 0;
  std::optional<double> max_age;
  std::uint32_t max_age_max = 0;
  double failures = 0.0;
  double risk = 0.0;
  std::optional<double> psnr;
};

// pixel_fragments is row-major with row 0 at the bottom, as fragments' y.
std::vector<Fragment> synthetic_stream(const std::vector<std::uint32_t>& counts, Extent screen, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> depth(0.0f, 1.0f);
  std::vector<Fragment> out;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      for (std::uint32_t i = 0; i < counts[x + std::size_t{y} * screen.x]; ++i)
        out.push_back(Fragment{x, y, depth(rng), static_cast<std::uint32_t>(out.size())});
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

// `beyond_amax`: the fragments beyond AMAX over every pixel, when any pixel
// has more than AMAX (then every load fails them).
Prediction predict_ha(const ExactCapture& c, Extent screen, double load, const PlanSettings& s,
                      std::optional<std::uint64_t> beyond_amax) {
  Prediction p;
  p.spec.load = load;
  if (s.age_bits != HABUFFER_DEFAULT_AGE_BITS) p.spec.age_bits = s.age_bits;
  TechniqueConfig config;
  config.buffer.screen = screen;
  config.buffer.age_bits = s.age_bits;
  config.buffer.table = table_for_load(screen, c.fragments, load);
  p.memory = memory_model_bytes(config, config.buffer.table.area());
  double sum_max = 0.0, lost = 0.0, losing = 0.0;
  if (beyond_amax) {
    // Simulating would probe AMAX slots for each fragment beyond it, for
    // nothing: every trial loses at least the excess.
    const std::uint32_t amax = config.buffer.record_layout().max_age();
    p.max_age = amax;
    p.max_age_max = amax;
    p.failures = static_cast<double>(*beyond_amax);
    p.risk = 1.0;
    p.psnr = kInf;
    return p;
  }
  for (std::uint32_t t = 0; t < s.trials; ++t) {
    SimulatorConfig sc;
    sc.screen = screen;
    sc.table = config.buffer.table;
    sc.age_bits = s.age_bits;
    sc.seed = s.seed + 1000 + t;  // offsets apart from the renders' (seed + repetition)
    ProbeSimulator sim(sc);
    sim.insert(synthetic_stream(c.pixel_fragments, screen, s.seed + t));
    const SimulatorTotals tot = sim.totals();
    std::uint32_t max_age = 0;
    for (std::size_t a = 0; a < tot.age_histogram.size(); ++a)
      if (tot.age_histogram[a] > 0) max_age = static_cast<std::uint32_t>(a);
    sum_max += max_age;
    p.max_age_max = std::max(p.max_age_max, max_age);
    lost += static_cast<double>(tot.counters.failures());
    losing += tot.counters.failures() > 0 ? 1.0 : 0.0;
  }
  p.max_age = sum_max / s.trials;
  p.failures = lost / s.trials;
  p.risk = losing / s.trials;
  p.psnr = kInf;
  return p;
}

// The fragments a truncating technique keeps: per pixel the `k` nearest
// (k-buffer) or the first `k` to arrive (fixed arrays).
std::vector<Fragment> truncated(const std::vector<Fragment>& stream, Extent screen, std::uint32_t k, bool nearest) {
  std::vector<std::vector<Fragment>> per_pixel(screen.area());
  for (const Fragment& f : stream) per_pixel[f.x + std::size_t{f.y} * screen.x].push_back(f);
  std::vector<Fragment> out;
  for (auto& list : per_pixel) {
    if (nearest)
      std::stable_sort(list.begin(), list.end(), [](const Fragment& a, const Fragment& b) { return a.depth < b.depth; });
    for (std::size_t i = 0; i < list.size() && i < k; ++i) out.push_back(list[i]);
  }
  return out;
}

Prediction predict_layers(const ExactCapture& c, Extent screen, Technique technique, std::uint32_t k) {
  Prediction p;
  p.spec.technique = technique;
  p.spec.layers = k;
  TechniqueConfig config;
  config.technique = technique;
  config.buffer.screen = screen;
  config.buffer.table = screen;
  config.layers = k;
  p.memory = memory_model_bytes(config, 0);
  std::uint64_t over = 0;
  for (const std::uint32_t n : c.pixel_fragments) over += n > k ? n - k : 0;
  p.failures = static_cast<double>(over);
  p.risk = over > 0 ? 1.0 : 0.0;
  if (over == 0) {
    p.psnr = kInf;
  } else {
    const Image image = reference_image(truncated(c.stream, screen, k, descriptor(technique).overflow_keeps_nearest), screen, c.backgrounds);
    p.psnr = compare_pixels(image, c.reference).psnr;
  }
  return p;
}

Prediction predict_lists(const ExactCapture& c, Extent screen, Technique technique) {
  Prediction p;
  p.spec.technique = technique;
  p.spec.load = 1.0;
  TechniqueConfig config;
  config.technique = technique;
  config.buffer.screen = screen;
  config.buffer.table = screen;
  config.pool_capacity = std::max<std::uint64_t>(1, c.fragments);
  p.memory = memory_model_bytes(config, config.pool_capacity);
  p.psnr = kInf;
  return p;
}

// Bytes per fragment of the capture.
double per_fragment(const Prediction& p, std::uint64_t fragments) {
  return static_cast<double>(p.memory) / static_cast<double>(fragments);
}

bool within_budget(const Prediction& p, std::uint64_t fragments, const PlanSettings& s) {
  return !s.memory_budget || per_fragment(p, fragments) <= *s.memory_budget;
}

// The aim: lossless (no trial lost anything), or a predicted PSNR that meets
// the target (a hash table's only without failure risk).
bool meets_aim(const Prediction& p, const PlanSettings& s) {
  return s.target_psnr ? (p.psnr && *p.psnr >= *s.target_psnr && (!uses_table(p.spec.technique) || p.risk == 0.0))
                       : p.risk == 0.0;
}

// Accuracy for the fallback under a budget: the predicted PSNR, -inf for a
// hash table that may fail (its failures' PSNR is not predicted).
double accuracy(const Prediction& p) {
  if (!p.psnr || (uses_table(p.spec.technique) && p.risk > 0.0)) return -kInf;
  return *p.psnr;
}

// The recommendation (plan.h): least memory among those meeting the aim
// within the budget; else, with a budget, the most accurate within it.
// `fallback` is set when the second rule chose.
const Prediction* recommended(const std::vector<Prediction>& preds, std::uint64_t fragments, const PlanSettings& s,
                              bool& fallback) {
  fallback = false;
  const Prediction* best = nullptr;
  for (const Prediction& p : preds)
    if (meets_aim(p, s) && within_budget(p, fragments, s) && (!best || p.memory < best->memory)) best = &p;
  if (best || !s.memory_budget) return best;
  const auto better = [](const Prediction& a, const Prediction& b) {
    if (accuracy(a) != accuracy(b)) return accuracy(a) > accuracy(b);
    if (a.failures != b.failures) return a.failures < b.failures;
    return a.memory < b.memory;
  };
  for (const Prediction& p : preds)
    if (within_budget(p, fragments, s) && (!best || better(p, *best))) best = &p;
  fallback = best != nullptr;
  return best;
}

// One prediction as a row of the plan's table.
ResultRow plan_row(const Prediction& p, std::uint64_t fragments, const PlanSettings& s, bool best) {
  ResultRow row;
  row.set("technique", p.spec.label()).set("memory_bytes", p.memory).set("bytes_per_fragment", per_fragment(p, fragments));
  if (p.max_age) row.set("predicted_max_age", *p.max_age).set("predicted_max_age_max", p.max_age_max);
  row.set("predicted_failures", p.failures).set("failure_risk", p.risk);
  if (p.psnr) row.set("predicted_psnr", *p.psnr);
  row.set("lossless", p.risk == 0.0);
  if (s.target_psnr) row.set("meets_target", p.psnr && *p.psnr >= *s.target_psnr);
  if (s.memory_budget) row.set("within_budget", within_budget(p, fragments, s));
  row.set("recommended", best);
  return row;
}

// The settings' own rules, checked before any capture.
void check_settings(const PlanSettings& s) {
  if (s.trials == 0) throw std::invalid_argument("plan needs at least one trial");
  if (s.target_psnr && !(std::isfinite(*s.target_psnr) && *s.target_psnr > 0.0))
    throw std::invalid_argument("target PSNR " + std::to_string(*s.target_psnr) + " is not a finite PSNR above 0 dB");
  if (s.memory_budget && !(std::isfinite(*s.memory_budget) && *s.memory_budget >= 0.0))
    throw std::invalid_argument("memory budget " + std::to_string(*s.memory_budget) +
                                " is not a finite number of bytes per fragment at least 0");
}

}  // namespace

ResultTable plan_from_capture(const ExactCapture& c, Extent screen, const PlanSettings& s) {
  check_settings(s);
  if (c.fragments == 0) throw std::invalid_argument("the scene puts no fragment on the screen: nothing to plan");
  std::vector<Prediction> preds;
  const std::uint32_t deepest = *std::max_element(c.pixel_fragments.begin(), c.pixel_fragments.end());
  const double max_load = static_cast<double>(c.fragments) / static_cast<double>(screen.area());
  const std::uint32_t amax = RecordLayout(Layout::L64, s.age_bits).max_age();
  const std::optional<PixelDepth> too_deep = pixel_counted_beyond(c.pixel_fragments, screen, amax);
  std::optional<std::uint64_t> beyond_amax;
  if (too_deep) {
    beyond_amax = 0;
    for (const std::uint32_t n : c.pixel_fragments) *beyond_amax += n > amax ? n - amax : 0;
  }
  std::uint64_t done = 0;
  const std::uint64_t total = s.loads.size();
  for (const double l : s.loads) {
    if (l <= max_load) preds.push_back(predict_ha(c, screen, l, s, beyond_amax));
    if (s.on_progress) s.on_progress(++done, total);
  }
  preds.push_back(predict_lists(c, screen, Technique::Lists));
  preds.push_back(predict_lists(c, screen, Technique::SortedLists));
  std::vector<std::uint32_t> ks{1, 2, 4, 8, 16};
  ks.push_back(deepest);
  std::sort(ks.begin(), ks.end());
  ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
  for (const std::uint32_t k : ks) {
    if (k > deepest) continue;
    preds.push_back(predict_layers(c, screen, Technique::KBuffer, k));
    preds.push_back(predict_layers(c, screen, Technique::Arrays, k));
  }
  bool fallback = false;
  const Prediction* best = recommended(preds, c.fragments, s, fallback);
  ResultTable table;
  table.title = "plan";
  for (const Prediction& p : preds) table.rows.push_back(plan_row(p, c.fragments, s, &p == best));
  std::vector<std::uint64_t> depth(deepest + 1, 0);
  for (const std::uint32_t n : c.pixel_fragments) ++depth[n];
  std::string hist;
  for (std::size_t d = 0; d < depth.size(); ++d)
    if (depth[d]) hist += (hist.empty() ? "" : " ") + std::to_string(d) + ":" + std::to_string(depth[d]);
  table.notes["fragments"] = std::to_string(c.fragments);
  table.notes["max_depth_complexity"] = std::to_string(deepest);
  if (too_deep)
    table.notes["ha_beyond_amax"] =
        too_deep_message(*too_deep, s.age_bits) + "; the ha rows are predicted without simulation";
  table.notes["depth_complexity_histogram"] = hist + " (fragments per pixel : pixels)";
  table.notes["recommendation"] =
      best ? best->spec.label() : std::string(s.memory_budget ? "none fits the memory budget" : "none meets the target");
  if (s.memory_budget) {
    const std::string aim = s.target_psnr ? "the target" : "losslessness";
    table.notes["budget"] = shortest_text(*s.memory_budget) + " bytes per fragment: " +
                            (!best       ? std::string("no configuration fits it")
                             : fallback ? "no configuration meets " + aim + " within it; the most accurate within it"
                                        : "the least memory meeting " + aim + " within it");
  }
  table.notes["model"] =
      "HA-buffer: SPEC 3's insertion (stats library model) of a synthetic stream with the scene's per-pixel counts and "
      "random depths, " + std::to_string(s.trials) + " seeds; k-buffer and arrays: the k nearest or first k fragments of "
      "the capture composited (SPEC 7) against the exact reference; lists: pool of exactly the fragments. Early cull "
      "is not planned (it needs the opacities' order).";
  table.provenance.renderer = "cpu (model)";
  return table;
}

ResultTable run_plan(const Workload& workload, const PlanSettings& s) {
  check_settings(s);
  ResultTable t = plan_from_capture(workload.capture(), workload.size(), s);
  t.notes["scene"] = workload.label();
  t.notes["size"] = workload.size().str();
  return t;
}

}  // namespace habuffer::harness
