// The CPU HA-buffer's phases on real scenes (issue 36), each variant on the
// same captured frame so that one run gives after-vs-before ratios: the
// jump start through the shared GLSL step (the reference) or the
// specialised one, one pixel at a time or 16 interleaved; and the composite
// one pixel at a time (HaBuffer::composite, the shared walk) or as the
// wavefront composite_image runs. Every variant builds the same table and
// image (tests/test_insert_order.cpp, test_compositing.cpp). One thread,
// 512x512, the table at load 0.55 (the automatic size). Run with
// --benchmark_enable_random_interleaving and repetitions.
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "bench_common.h"
#include "habuffer/render/render_job.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::bench {
namespace {

constexpr Extent kSceneScreen{512, 512};
const char* const kScenes[] = {"spider", "wuson", "engine", "hairball"};

// The scene's fragments at 512x512 from its default view, captured once.
const std::vector<Fragment>& scene_fragments(std::int64_t scene) {
  static std::map<std::int64_t, std::vector<Fragment>> cache;
  auto it = cache.find(scene);
  if (it != cache.end()) return it->second;
  gl_bench_context();
  const Scene s = make_scene(kScenes[scene], {});
  RenderSettings r;
  r.path = RenderPath::Cpu;
  r.config.screen = kSceneScreen;
  r.camera = {s.default_yaw, s.default_pitch, 45.0f};
  r.keep_fragments = true;
  return cache.emplace(scene, render_scene(s, r).fragments).first->second;
}

void BM_HaSceneInsert(benchmark::State& state) {
  const auto& frags = scene_fragments(state.range(0));
  HaBuffer buffer = buffer_for_load(kSceneScreen, frags.size(), 0.55);
  InsertOptions o;
  o.order = InsertOrder::Pixel;
  o.step = state.range(1) != 0 ? InsertStep::Specialised : InsertStep::Shared;
  o.interleave = state.range(2) != 0;
  for (auto _ : state) {
    state.PauseTiming();
    buffer.reset();
    state.ResumeTiming();
    benchmark::DoNotOptimize(buffer.insert(frags, o));
  }
  state.SetLabel(kScenes[state.range(0)]);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * frags.size()));
}
BENCHMARK(BM_HaSceneInsert)
    ->ArgNames({"scene", "specialised", "lanes"})
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_HaSceneComposite(benchmark::State& state) {
  const auto& frags = scene_fragments(state.range(0));
  HaBuffer buffer = buffer_for_load(kSceneScreen, frags.size(), 0.55);
  buffer.insert(frags);
  const bool wavefront = state.range(1) != 0;
  std::vector<glm::vec4> image(kSceneScreen.area());
  for (auto _ : state) {
    if (wavefront) {
      image = buffer.composite_image(glm::vec3(1.0f), 1);
    } else {
      for (std::uint32_t y = 0; y < kSceneScreen.y; ++y)
        for (std::uint32_t x = 0; x < kSceneScreen.x; ++x)
          image[x + std::size_t{y} * kSceneScreen.x] = buffer.composite(x, y, glm::vec3(1.0f));
    }
    benchmark::DoNotOptimize(image.data());
  }
  state.SetLabel(kScenes[state.range(0)]);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSceneScreen.area()));
}
BENCHMARK(BM_HaSceneComposite)
    ->ArgNames({"scene", "wavefront"})
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace habuffer::bench
