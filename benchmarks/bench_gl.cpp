// GPU path: compute-shader insertion on the machine's OpenGL (llvmpipe here),
// fragments per second vs load, including the upload of the stream and the
// read-back of the six counters (what `build-lists --path gl` will pay).
#include <benchmark/benchmark.h>

#include "bench_common.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"

namespace habuffer::bench {
namespace {

void run_gl_insert(benchmark::State& state, gl::AtomicMode mode, Layout layout) {
  static gl::EglContext context;
  context.make_current();
  const double load = static_cast<double>(state.range(0)) / 100.0;
  const Extent screen{512, 512};
  const auto& frags = stream(StreamKind::Coherent, screen, std::uint64_t{1} << 18);
  BufferConfig c;
  c.screen = screen;
  c.table = table_for_load(screen, frags.size(), load);
  c.layout = layout;
  gl::ComputeInserter gpu(c, OffsetSequence::random(c.table, c.record_layout().max_age(), 7), mode);
  Counters n;
  for (auto _ : state) {
    state.PauseTiming();
    gpu.clear();
    state.ResumeTiming();
    n = gpu.insert(frags);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * frags.size()));
  state.counters["failed"] = static_cast<double>(n.failures());
}
void BM_GlInsertNative32(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Native32, Layout::L32); }
void BM_GlInsertEmulated64(benchmark::State& s) { run_gl_insert(s, gl::AtomicMode::Emulated64, Layout::L64); }
BENCHMARK(BM_GlInsertEmulated64)->ArgName("load")->Arg(10)->Arg(50)->Arg(80)->Arg(95)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlInsertNative32)->ArgName("load")->Arg(10)->Arg(50)->Arg(80)->Arg(95)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace habuffer::bench
