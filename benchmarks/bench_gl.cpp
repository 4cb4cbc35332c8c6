// GPU path on the machine's OpenGL (llvmpipe here; scripts/gpu_checks.sh on a
// GPU). Three families:
//  - BM_GlInsert<Mode>/load:L/log2n:N: the compute entry on 2^N coherent
//    synthetic fragments, fragments per second vs load (N = 18 on 512x512,
//    where a GPU is dispatch-bound; N = 24 on 4096x4096, the same density).
//  - BM_GlCaptured/<scene>/<order>/<mode>: a scene's captured stream (what
//    render's gather inserts) through the compute entry, in arrival order or
//    in pixel order (sorted on the host by pixel, nearest first), with the
//    module's variants as arguments (ModuleVariant: slot read-first, max-age
//    read-first, slot-write tally).
//  - BM_GlGather/<scene>/<technique>: render's gather of a scene in steady
//    state: one untimed frame on the same container first (its time is the
//    counter first_frame_ms), then frames on it; with or without the
//    per-fragment bookkeeping render used to pay in every frame (the slot-write
//    tally and the per-pixel counts of the heat maps), and the module variants.
// The time is the gather (dispatch or draw to glFinish, wall clock; llvmpipe's
// timer queries are not usable), plus the resolve for BM_GlGather; the clear
// pass and buffer resets run outside it and are the counter clear_ms.
#include <benchmark/benchmark.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include "bench_common.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/gl/techniques/ha/gl_ha_table.h"
#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/render/render_job.h"
#include "habuffer/render/resolve_target.h"
#include "habuffer/render/scene_renderer.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::bench {
namespace {

bool runnable(gl::AtomicMode mode) {
  const auto modes = gl::runnable_atomic_modes(gl::query_gl_info());
  return std::find(modes.begin(), modes.end(), mode) != modes.end();
}

Layout layout_of(gl::AtomicMode mode) { return mode == gl::AtomicMode::Native32 ? Layout::L32 : Layout::L64; }

// The module variant of a benchmark's arguments from index `first` on:
// slot_rf, age_rf, writes (0 or 1 each).
gl::ModuleVariant variant_of(const benchmark::State& state, int first) {
  gl::ModuleVariant v;
  v.slot_read_first = state.range(first) != 0;
  v.max_age_read_first = state.range(first + 1) != 0;
  v.count_writes = state.range(first + 2) != 0;
  return v;
}

// Frames of `buffer` inserting what `inserter` holds, the dispatch timed to
// glFinish inside the gather, after one untimed frame (llvmpipe compiles a
// shader at its first dispatch; a GPU driver may too); counters: failures,
// the clear pass and resets, and that first frame.
void time_compute_frames(benchmark::State& state, gl::GlHaBuffer& buffer, const gl::ComputeInserter& inserter) {
  double seconds = 0.0;
  const auto timed_frame = [&] {
    return buffer.frame([&] {
      const auto t0 = std::chrono::steady_clock::now();
      inserter.dispatch();
      glFinish();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    });
  };
  gl::FrameReport report = timed_frame();
  state.counters["first_frame_ms"] = seconds * 1e3;
  double clear_ms = 0.0;
  for (auto _ : state) {
    report = timed_frame();
    state.SetIterationTime(seconds);
    clear_ms += report.clear.wall_ms + report.reset.wall_ms;
  }
  const auto n = static_cast<std::int64_t>(inserter.uploaded());
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["fragments"] = static_cast<double>(n);
  state.counters["failed"] = static_cast<double>(report.counters.failures());
  state.counters["deferred"] = static_cast<double>(report.deferred);
  if (report.slot_writes) state.counters["slot_writes"] = static_cast<double>(*report.slot_writes);
  state.counters["clear_ms"] = clear_ms / static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
}

// Synthetic coherent stream: load:L (percent), log2n:N.
void run_gl_insert(benchmark::State& state, gl::AtomicMode mode) {
  gl_bench_context();
  if (!runnable(mode)) {
    state.SkipWithError(("atomic mode " + gl::to_string(mode) + " does not run on this OpenGL").c_str());
    return;
  }
  const double load = static_cast<double>(state.range(0)) / 100.0;
  const auto log2n = static_cast<std::uint32_t>(state.range(1));
  const std::uint32_t side = 512u << ((log2n - 18) / 2);  // one fragment per pixel on average, as 2^18 on 512x512
  const Extent screen{side, side};
  const auto& frags = stream(StreamKind::Coherent, screen, std::uint64_t{1} << log2n);
  BufferConfig c;
  c.screen = screen;
  c.table = table_for_load(screen, frags.size(), load);
  c.layout = layout_of(mode);
  OffsetSource offsets;
  offsets.seed = 7;
  gl::GlHaBuffer buffer(c, offsets, mode);
  gl::ComputeInserter inserter(buffer);
  inserter.upload(frags);
  time_compute_frames(state, buffer, inserter);
}
void BM_GlInsertNative32(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Native32); }
void BM_GlInsertNative64(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Native64); }
void BM_GlInsertEmulated64(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Emulated64); }
void insert_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"load", "log2n"});
  for (int load : {10, 30, 50, 70, 80, 90, 95}) b->Args({load, 18});
  b->Args({50, 24})->Args({80, 24});
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_GlInsertNative32)->Apply(insert_args);
BENCHMARK(BM_GlInsertNative64)->Apply(insert_args);
BENCHMARK(BM_GlInsertEmulated64)->Apply(insert_args);

// The scene's default view at side x side, framed as render frames it.
Camera default_camera(const Scene& scene, std::uint32_t side) {
  return frame_scene(scene, {scene.default_yaw, scene.default_pitch, 45.0f}, {side, side});
}

// The fragments render's gather inserts for a scene's default view, in the
// rasterizer's order (captured once per scene and side).
const std::vector<Fragment>& captured(const std::string& name, std::uint32_t side) {
  static std::map<std::pair<std::string, std::uint32_t>, std::vector<Fragment>> cache;
  const auto key = std::make_pair(name, side);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const Scene scene = make_scene(name, {});
  RenderSettings s;
  s.path = RenderPath::Cpu;
  s.technique = Technique::Blend;  // the cheapest: one pass, nothing to grow (as harness::Workload::capture)
  s.keep_fragments = true;
  s.config.screen = {side, side};
  s.camera = {scene.default_yaw, scene.default_pitch, 45.0f};
  return cache.emplace(key, render_scene(scene, s).fragments).first->second;
}

// Pixel order: by pixel, each pixel's fragments nearest first (ties in arrival order).
std::vector<Fragment> in_pixel_order(std::vector<Fragment> f) {
  std::stable_sort(f.begin(), f.end(), [](const Fragment& a, const Fragment& b) {
    return std::tie(a.y, a.x, a.depth) < std::tie(b.y, b.x, b.depth);
  });
  return f;
}

// side, load (percent), slot_rf, age_rf, writes.
void run_captured(benchmark::State& state, const std::string& scene, bool pixel_order, gl::AtomicMode mode) {
  gl_bench_context();
  if (!runnable(mode)) {
    state.SkipWithError(("atomic mode " + gl::to_string(mode) + " does not run on this OpenGL").c_str());
    return;
  }
  const auto side = static_cast<std::uint32_t>(state.range(0));
  const double load = static_cast<double>(state.range(1)) / 100.0;
  const std::vector<Fragment>& arrival = captured(scene, side);
  const std::vector<Fragment> frags = pixel_order ? in_pixel_order(arrival) : arrival;
  BufferConfig c;
  c.screen = {side, side};
  c.table = table_for_load(c.screen, frags.size(), load);
  c.layout = layout_of(mode);
  gl::GlFrameOptions o;
  o.module = variant_of(state, 2);
  gl::GlHaBuffer buffer(c, OffsetSource{}, mode, o);
  gl::ComputeInserter inserter(buffer);
  inserter.upload(frags);
  time_compute_frames(state, buffer, inserter);
}

void captured_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"side", "load", "slot_rf", "age_rf", "writes"});
  for (int side : {256, 512, 1024}) {
    for (int load : {30, 55, 80}) b->Args({side, load, 1, 0, 0});
    b->Args({side, 55, 0, 0, 0})->Args({side, 55, 1, 1, 0})->Args({side, 55, 0, 1, 0})->Args({side, 55, 1, 0, 1});
  }
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

// A GL path technique with placeholder sizes (the screen), as render makes it before its counting pass.
std::unique_ptr<gl::GlTechnique> placeholder_technique(Technique t, float cull, Extent screen, gl::AtomicMode mode) {
  TechniqueConfig c;
  c.technique = t;
  c.buffer.screen = screen;
  c.buffer.table = screen;
  c.buffer.layout = layout_of(mode);
  c.buffer.early_cull_tau = cull;
  c.pool_capacity = screen.area();
  return gl::make_gl_technique(c, OffsetSource{}, mode);
}

// Sizes for `fragments` as render's automatic sizes do: the HA-buffer's
// table at load 0.55, the lists' pool at 0.8.
void size_for(gl::GlTechnique& t, std::uint64_t fragments) {
  TechniqueConfig wanted;
  wanted.technique = t.technique();
  if (uses_table(wanted.technique)) wanted.buffer.table = table_for_load(t.screen(), fragments, 0.55);
  wanted.pool_capacity = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(fragments) / 0.8)));
  t.fit_automatic_size(wanted);
}

// side, bookkeeping (0: none in the gather; a driver that asks for the call
// count (llvmpipe) gets it from a counting pass after the gather's clock;
// 1: the slot-write tally and every per-pixel count in the gather, as render
// paid in every frame before issue 26), slot_rf, age_rf.
void run_gather(benchmark::State& state, const std::string& name, Technique technique, float cull) {
  gl_bench_context();
  const auto side = static_cast<std::uint32_t>(state.range(0));
  const bool bookkeeping = state.range(1) != 0;
  const Extent screen{side, side};
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode) {
    state.SkipWithError("no 64-bit shader types");
    return;
  }
  const Scene scene = make_scene(name, {});
  const Camera camera = default_camera(scene, side);
  gl::GlFrameOptions o;
  o.module = variant_of(state, 2);
  o.module.count_writes = bookkeeping;
  gl::GlFrameDriver driver(placeholder_technique(technique, cull, screen, *mode), o);
  SceneRenderer renderer(scene, screen, driver, {bookkeeping, bookkeeping});
  ResolveTarget target(screen);
  renderer.draw_opaque(camera, glm::vec3(1.0f));
  size_for(driver.technique(), renderer.count_fragments(camera));
  const auto frame = [&] {
    gl::FrameReport r = driver.frame([&] { renderer.gather(camera); }, [&] { return renderer.inserted(); });
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer());
    r.sort.wall_ms += driver.resolve(glm::vec3(1.0f), renderer.opaque_colour_texture()).wall_ms;  // sort + resolve
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    return r;
  };
  const gl::FrameReport first = frame();  // the cold frame, on the same container as the timed ones
  gl::FrameReport last;
  double gather_ms = 0.0, resolve_ms = 0.0, clear_ms = 0.0, gpu_ms = 0.0;
  for (auto _ : state) {
    last = frame();
    state.SetIterationTime((last.gather.wall_ms + last.sort.wall_ms) * 1e-3);
    gather_ms += last.gather.wall_ms;
    resolve_ms += last.sort.wall_ms;
    clear_ms += last.clear.wall_ms + last.reset.wall_ms;
    gpu_ms += last.gather.gpu_ms;
  }
  const auto n = static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(last.counters.fragments));
  state.counters["first_frame_ms"] = first.gather.wall_ms + first.sort.wall_ms;
  state.counters["gather_ms"] = gather_ms / n;
  state.counters["resolve_ms"] = resolve_ms / n;
  state.counters["clear_ms"] = clear_ms / n;
  state.counters["gather_gpu_ms"] = gpu_ms / n;  // GL timestamps: meaningful on a GPU, not on llvmpipe
  state.counters["fragments"] = static_cast<double>(last.counters.fragments);
  state.counters["failed"] = static_cast<double>(last.counters.failures());
}

// With and without the bookkeeping; for the HA-buffer without early cull
// also the module's read-first variants (the others insert no slot records).
void gather_args(benchmark::internal::Benchmark* b, bool variants) {
  b->ArgNames({"side", "bookkeeping", "slot_rf", "age_rf"});
  for (int side : {256, 512, 1024}) {
    for (int bookkeeping : {0, 1}) b->Args({side, bookkeeping, 1, 0});
    if (variants) b->Args({side, 0, 0, 0})->Args({side, 0, 1, 1});
  }
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

const bool registered = [] {
  for (const char* scene : {"hairball", "engine"})
    for (const auto& [pixel_order, order] : {std::pair{false, "arrival"}, std::pair{true, "pixel"}})
      for (gl::AtomicMode mode : {gl::AtomicMode::Native32, gl::AtomicMode::Native64, gl::AtomicMode::Emulated64})
        benchmark::RegisterBenchmark(
            ("BM_GlCaptured/" + std::string(scene) + "/" + order + "/" + gl::to_string(mode)).c_str(),
            [=](benchmark::State& st) { run_captured(st, scene, pixel_order, mode); })
            ->Apply(captured_args);
  struct Gathered {
    const char* label;
    Technique technique;
    float cull;
  };
  for (const char* scene : {"engine", "hairball", "spider"})
    for (const Gathered& g : {Gathered{"ha", Technique::Ha, 0.0f}, Gathered{"ha-cull99", Technique::Ha, 0.99f},
                              Gathered{"lists", Technique::Lists, 0.0f}})
      gather_args(benchmark::RegisterBenchmark(("BM_GlGather/" + std::string(scene) + "/" + g.label).c_str(),
                                               [=](benchmark::State& st) { run_gather(st, scene, g.technique, g.cull); }),
                  uses_table(g.technique) && g.cull == 0.0f);
  return true;
}();

}  // namespace
}  // namespace habuffer::bench
