// `habuffer render`'s frame on the machine's OpenGL (llvmpipe here): the
// gather of real scenes through the GLSL module (insertion included), and
// the resolve, per fragment. Each iteration renders one frame of a fresh
// setup; the time is the gather's wall clock (dispatch to glFinish), the
// resolve is reported as a counter.
#include <benchmark/benchmark.h>

#include "habuffer/gl/egl_context.h"
#include "habuffer/render/render_job.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::bench {
namespace {

void run_render(benchmark::State& state, const char* name, float tau) {
  static gl::EglContext context;
  context.make_current();
  const auto side = static_cast<std::uint32_t>(state.range(0));
  const Scene scene = make_scene(name, {});
  RenderSettings s;
  s.config.screen = {side, side};
  s.config.early_cull_tau = tau;
  s.camera = {scene.default_yaw, scene.default_pitch, 45.0f};
  FrameStats last;
  double resolve_ms = 0.0;
  for (auto _ : state) {
    const RenderResult r = render_scene(scene, s);
    last = r.frames.back();
    state.SetIterationTime(last.gather_ms * 1e-3);
    resolve_ms += last.resolve_ms;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(last.counters.fragments));
  state.counters["fragments"] = static_cast<double>(last.counters.fragments);
  state.counters["stored"] = static_cast<double>(last.counters.stored());
  state.counters["load"] = last.load_factor;
  state.counters["max_age"] = last.max_age;
  state.counters["resolve_ms"] = resolve_ms / static_cast<double>(state.iterations());
}

void BM_RenderEngine(benchmark::State& s) { run_render(s, "engine", 0.0f); }
void BM_RenderEngineCull99(benchmark::State& s) { run_render(s, "engine", 0.99f); }
void BM_RenderHairball(benchmark::State& s) { run_render(s, "hairball", 0.0f); }
void BM_RenderHairballCull99(benchmark::State& s) { run_render(s, "hairball", 0.99f); }
BENCHMARK(BM_RenderEngine)->ArgName("side")->Arg(512)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RenderEngineCull99)->ArgName("side")->Arg(512)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RenderHairball)->ArgName("side")->Arg(512)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RenderHairballCull99)->ArgName("side")->Arg(512)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace habuffer::bench
