// Every technique's frame of a real scene at 512x512, on the GPU path
// (llvmpipe here) and the CPU path, beside the two floors in the same run:
// plain blending (no lists) and one atomic add per fragment. The time of a
// technique is its gather plus its resolve (the sort pass of lists and
// arrays included; on the CPU path the sort runs in the insert, so in the
// gather); counters give each part, the memory measured and by formula,
// and the fragments dropped. Run with --benchmark_enable_random_interleaving
// and repetitions so the machine's drift hits every technique alike.
#include <benchmark/benchmark.h>

#include <optional>
#include <string>

#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/render/gl_floors.h"
#include "habuffer/render/render_job.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::bench {
namespace {

constexpr std::uint32_t kSide = 512;

gl::EglContext& context() {
  static gl::EglContext ctx;
  ctx.make_current();
  return ctx;
}

// One technique with its knobs, as the table names it.
struct Variant {
  const char* label;
  Technique technique;
  float cull_tau = 0.0f;
  bool saturation = false;
  std::uint32_t layers = HABUFFER_DEFAULT_LAYERS;
  bool occupancy = false;
};

const Variant kVariants[] = {
    {"ha", Technique::Ha},
    {"ha-cull99", Technique::Ha, 0.99f},
    {"ha-cull99-sat", Technique::Ha, 0.99f, true},
    {"lists", Technique::Lists},
    {"arrays", Technique::Arrays, 0.0f, false, 64},
    {"sorted-lists", Technique::SortedLists},
    {"sorted-lists-cull99", Technique::SortedLists, 0.99f},
    {"sorted-lists-cull99-sat", Technique::SortedLists, 0.99f, true},
    {"kbuffer4", Technique::KBuffer, 0.0f, false, 4},
    {"kbuffer8", Technique::KBuffer, 0.0f, false, 8},
    {"kbuffer8-occ", Technique::KBuffer, 0.0f, false, 8, true},
    {"kbuffer16", Technique::KBuffer, 0.0f, false, 16},
    {"wboit", Technique::Wboit},
    {"blend", Technique::Blend},
};

// "planes-front" and "planes-back": 32 full-screen planes in that order.
Scene bench_scene(const std::string& name) {
  SceneOptions o;
  if (name.rfind("planes", 0) == 0) {
    o.count = 32;
    o.order = name == "planes-front" ? PlaneOrder::FrontToBack : PlaneOrder::BackToFront;
    return make_scene("planes", o);
  }
  return make_scene(name, o);
}

void run_technique(benchmark::State& state, const std::string& name, RenderPath path, const Variant& v) {
  context();
  const Scene scene = bench_scene(name);
  RenderSettings s;
  s.path = path;
  s.technique = v.technique;
  s.config.screen = {kSide, kSide};
  s.config.early_cull_tau = v.cull_tau;
  s.config.saturation = v.saturation;
  s.layers = v.layers;
  s.occupancy = v.occupancy;
  s.camera = {scene.default_yaw, scene.default_pitch, 45.0f};
  // Steady state, as `habuffer bench`: a warm-up frame of the same view on
  // the same buffers, then the timed one (the first frame's cold start,
  // fresh buffers and their first touch, is reported as first_frame_ms).
  s.frames = 2;
  s.orbit = false;
  FrameStats last;
  double first = 0.0;
  RenderResult r;
  double gather = 0.0, resolve = 0.0;
  for (auto _ : state) {
    r = render_scene(scene, s);
    last = r.frames.back();
    first += r.frames.front().gather_ms + r.frames.front().resolve_ms;
    state.SetIterationTime((last.gather_ms + last.resolve_ms) * 1e-3);
    gather += last.gather_ms;
    resolve += last.resolve_ms;
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["gather_ms"] = gather / n;
  state.counters["resolve_ms"] = resolve / n;
  state.counters["first_frame_ms"] = first / n;
  state.counters["fragments"] = static_cast<double>(last.counters.fragments);
  state.counters["dropped"] = static_cast<double>(last.counters.failures());
  state.counters["memory_MiB"] = static_cast<double>(r.memory_bytes) / (1 << 20);
  state.counters["model_MiB"] = static_cast<double>(r.memory_model_bytes) / (1 << 20);
  state.counters["load"] = last.load_factor;
}

void run_floor(benchmark::State& state, const std::string& name, bool blend) {
  context();
  std::optional<GlFloors> floors;
  try {
    floors.emplace(bench_scene(name), Extent{kSide, kSide});
  } catch (const gl::GlError& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) state.SetIterationTime((blend ? floors->blend_ms() : floors->atomic_ms()) * 1e-3);
  if (!blend) state.counters["fragments"] = static_cast<double>(floors->fragments());  // the blend floor counts nothing
}

const bool registered = [] {
  for (const char* scene : {"engine", "hairball", "planes-front", "planes-back"}) {
    for (const auto& [path, path_name] : {std::pair{RenderPath::Gl, "gl"}, std::pair{RenderPath::Cpu, "cpu"}})
      for (const Variant& v : kVariants) {
        benchmark::RegisterBenchmark(("BM_Technique/" + std::string(scene) + "/" + path_name + "/" + v.label).c_str(),
                                     [=](benchmark::State& st) { run_technique(st, scene, path, v); })
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(2);
      }
    for (const auto& [blend, floor] : {std::pair{true, "blend"}, std::pair{false, "atomic"}})
      benchmark::RegisterBenchmark(("BM_Floor/" + std::string(scene) + "/gl/" + floor).c_str(),
                                   [=](benchmark::State& st) { run_floor(st, scene, blend); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
  }
  return true;
}();

}  // namespace
}  // namespace habuffer::bench
