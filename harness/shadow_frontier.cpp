#include "habuffer/harness/shadow_frontier.h"

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"
#include "habuffer/opacity_shadow_map.h"
#include "habuffer/render/shadow_accuracy.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer::harness {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// One light buffer of the frontier: how it is named, and how it is built
// from the light's fragments into a lookup (its memory and stored records).
struct Built {
  ShadowLookup lookup;
  std::uint64_t memory_bytes = 0;
  std::uint64_t stored = 0;
  std::shared_ptr<const void> keep;  // what the lookup borrows
};
struct Variant {
  std::string light_buffer, parameter;
  std::function<Built(std::span<const Fragment>)> build;
};

// max_attempts 16 for the HA-buffer (its table grown until nothing is
// dropped), 1 for the k-buffer (whose lossless growth would double K: its
// drops are the approximation measured).
Built list_buffer(const TechniqueConfig& config, std::span<const Fragment> light, std::uint32_t threads,
                  RecordLayout layout, std::uint32_t bias) {
  InsertOptions options;
  options.threads = threads;
  const std::uint32_t attempts = uses_table(config.technique) ? 16 : 1;
  TechniqueBuild b = build_technique(config, OffsetSource{}, light, options, ResizePolicy{}, attempts);
  std::shared_ptr<const FragmentBuffer> buffer(std::move(b.buffer));
  Built out;
  out.lookup = buffer_lookup(*buffer, layout, bias);
  out.memory_bytes = memory_model_bytes(*buffer);
  out.stored = b.counters.stored();
  out.keep = buffer;
  return out;
}

std::vector<Variant> variants(Extent light_size, std::uint64_t fragments, std::uint32_t age_bits, std::uint32_t bias,
                              std::uint32_t threads) {
  const RecordLayout layout(Layout::L64, age_bits);
  const auto config = [=](Technique t, float tau, std::uint32_t k) {  // by value: the variants outlive this call
    TechniqueConfig c;
    c.technique = t;
    c.layers = k;
    c.buffer.screen = light_size;
    c.buffer.layout = Layout::L64;
    c.buffer.age_bits = age_bits;
    c.buffer.table = table_for_load(light_size, fragments, 0.55);
    c.buffer.early_cull_tau = tau;
    return c;
  };
  std::vector<Variant> v;
  for (const float tau : {0.0f, 0.99f, 0.9f})
    v.push_back({"ha", tau > 0.0f ? "cull " + std::to_string(tau).substr(0, 4) : "exact", [=](std::span<const Fragment> f) {
                   return list_buffer(config(Technique::Ha, tau, 1), f, threads, layout, bias);
                 }});
  for (const std::uint32_t k : {4u, 8u})
    v.push_back({"kbuffer", "k " + std::to_string(k), [=](std::span<const Fragment> f) {
                   return list_buffer(config(Technique::KBuffer, 0.0f, k), f, threads, layout, bias);
                 }});
  for (const std::uint32_t n : {16u, 64u})
    v.push_back({"opacity-map", std::to_string(n) + " slices", [=](std::span<const Fragment> f) {
                   auto map = std::make_shared<OpacityShadowMap>(light_size, n);
                   map->insert(f);
                   Built out;
                   out.lookup = [m = map.get()](const LightSample& at) {
                     return m->transmittance(at.pixel.x, at.pixel.y, at.depth);
                   };
                   out.memory_bytes = map->memory_bytes();
                   out.stored = f.size();
                   out.keep = map;
                   return out;
                 }});
  return v;
}

void set_scores(ResultRow& row, const ShadowAccuracy& a) {
  row.set("rmse", a.rmse).set("max_error", a.max_error).set("within_fraction", a.within_fraction)
      .set("rmse_outside_band", a.rmse_outside).set("max_error_outside_band", a.max_error_outside)
      .set("receivers", a.receivers).set("band", a.band).set("self_shadow", a.self_shadow);
}

// The view rendered once with the directional light, keeping what the
// variants are scored on: the view's fragments, the light's buffer and its
// captured stream.
RenderSettings lit_view_settings(const ShadowFrontierSettings& s) {
  RenderSettings r;
  r.config.screen = s.size;
  r.keep_fragments = true;
  ShadowSettings light;
  light.light.orthographic = true;
  light.light.direction = s.light_direction;
  light.light.size = s.light_size;
  light.read_back = true;
  light.capture = true;
  r.shadows = light;
  return r;
}

}  // namespace

ResultTable run_shadow_frontier(const WorkloadSpec& scene, const ShadowFrontierSettings& s) {
  if (!scene.fragments.empty())
    throw std::invalid_argument("the shadow frontier lights a scene: '" + scene.word + "' is a fragment file");
  if (s.repeats == 0) throw std::invalid_argument("--repeats must be at least 1");
  const Workload workload(scene, s.size);
  const RenderSettings r = lit_view_settings(s);
  const RenderResult res = workload.render(r);
  const LightStats& ls = *res.light;
  const ShadowSettings& light = *r.shadows;
  const RecordLayout layout(Layout::L64, light.age_bits);
  const TransmittanceReference reference(*workload.scene());
  const ShadowReceivers receivers{&res.camera, s.size, res.fragments, res.opaque_depth};
  const ShadowTruths truths = shadow_truths(reference, ls.view, layout, ls.bias_codes, receivers, s.max_receivers);

  ResultTable table;
  table.title = "shadow-frontier";
  table.provenance.renderer = res.device;
  const std::vector<Variant> all = variants(s.light_size, res.light_fragments.size(), light.age_bits, ls.bias_codes,
                                            s.threads);
  const std::uint64_t total = all.size() + 1;
  std::uint64_t done = 0;
  ResultRow gpu;
  gpu.set("light_buffer", "ha").set("parameter", "exact (gl)").set("memory_bytes", ls.memory_bytes)
      .set("build_ms", ls.build_ms).set("build_path", "gl").set("stored", ls.counters.stored());
  set_scores(gpu, score_shadows(truths, buffer_lookup(*res.light_buffer, layout, ls.bias_codes)));
  table.rows.push_back(gpu);
  if (s.on_progress) s.on_progress(++done, total);
  for (const Variant& v : all) {
    std::vector<double> ms;
    Built built;
    for (std::uint32_t rep = 0; rep < s.repeats; ++rep) {
      const auto t0 = Clock::now();
      built = v.build(res.light_fragments);
      ms.push_back(ms_since(t0));
    }
    ResultRow row;
    row.set("light_buffer", v.light_buffer).set("parameter", v.parameter).set("memory_bytes", built.memory_bytes)
        .set("build_ms", spread_of(ms).median).set("build_path", "cpu").set("stored", built.stored);
    set_scores(row, score_shadows(truths, built.lookup));
    table.rows.push_back(row);
    if (s.on_progress) s.on_progress(++done, total);
  }
  table.notes["workload"] = scene.word + " at " + s.size.str() + ", a directional light, map " + s.light_size.str() +
                            ", " + std::to_string(res.light_fragments.size()) + " light fragments";
  table.notes["receivers"] = "the view's inserted fragments and opaque pixels" +
                             (truths.stride > 1 ? ", every " + std::to_string(truths.stride) + "th" : std::string()) +
                             "; the reference ray-traced in double (habuffer/render/shadow_accuracy.h: bands)";
  table.notes["build_ms"] = "gl: the light pass on this GPU; cpu: the light buffer built from the captured light "
                            "stream on this CPU (median of --repeats)";
  table.notes["memory_bytes"] = "the light buffer's storage (memory_model for lists; (N + 1) floats per pixel for an "
                                "opacity map)";
  return table;
}

}  // namespace habuffer::harness
