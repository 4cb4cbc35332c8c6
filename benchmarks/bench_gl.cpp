// GPU path: compute-entry insertion on the machine's OpenGL (llvmpipe here),
// fragments per second vs load. The time is the gather alone (dispatch to
// finish, wall clock; llvmpipe's GL_TIME_ELAPSED is not usable); the stream is
// uploaded once and each iteration is one frame, so the clear pass of the
// previous frame runs outside the clock and is reported as `clear_ms`.
#include <benchmark/benchmark.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>

#include "bench_common.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/gl_ha_buffer.h"
#include "habuffer/gl/egl_context.h"

namespace habuffer::bench {
namespace {

void run_gl_insert(benchmark::State& state, gl::AtomicMode mode, Layout layout) {
  static gl::EglContext context;
  context.make_current();
  const auto modes = gl::runnable_atomic_modes(gl::query_gl_info());
  if (std::find(modes.begin(), modes.end(), mode) == modes.end()) {
    state.SkipWithError(("atomic mode " + gl::to_string(mode) + " does not run on this OpenGL").c_str());
    return;
  }
  const double load = static_cast<double>(state.range(0)) / 100.0;
  const Extent screen{512, 512};
  const auto& frags = stream(StreamKind::Coherent, screen, std::uint64_t{1} << 18);
  BufferConfig c;
  c.screen = screen;
  c.table = table_for_load(screen, frags.size(), load);
  c.layout = layout;
  OffsetSource offsets;
  offsets.seed = 7;
  gl::GlHaBuffer buffer(c, offsets, mode);
  gl::ComputeInserter inserter(buffer);
  inserter.upload(frags);
  gl::FrameReport report;
  double clear_ms = 0.0;
  for (auto _ : state) {
    double seconds = 0.0;
    report = buffer.frame([&] {
      const auto t0 = std::chrono::steady_clock::now();
      inserter.dispatch();
      glFinish();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    });
    state.SetIterationTime(seconds);
    clear_ms += report.clear.wall_ms;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * frags.size()));
  state.counters["failed"] = static_cast<double>(report.counters.failures());
  state.counters["clear_ms"] = clear_ms / static_cast<double>(std::max<std::int64_t>(state.iterations() - 1, 1));
}
void BM_GlInsertNative32(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Native32, Layout::L32); }
void BM_GlInsertNative64(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Native64, Layout::L64); }
void BM_GlInsertEmulated64(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Emulated64, Layout::L64); }
BENCHMARK(BM_GlInsertNative32)->ArgName("load")->Arg(10)->Arg(30)->Arg(50)->Arg(70)->Arg(80)->Arg(90)->Arg(95)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlInsertNative64)->ArgName("load")->Arg(10)->Arg(30)->Arg(50)->Arg(70)->Arg(80)->Arg(90)->Arg(95)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlInsertEmulated64)->ArgName("load")->Arg(10)->Arg(30)->Arg(50)->Arg(70)->Arg(80)->Arg(90)->Arg(95)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace habuffer::bench
