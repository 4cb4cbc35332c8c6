// Traversal and compositing of the whole screen after a build.
#include <benchmark/benchmark.h>

#include "bench_common.h"

namespace habuffer::bench {
namespace {

void BM_CompositeImage(benchmark::State& state) {
  const double load = static_cast<double>(state.range(0)) / 100.0;
  const auto& frags = stream(StreamKind::Coherent);
  HaBuffer buffer = buffer_for_load(kScreen, frags.size(), load);
  buffer.insert(frags);
  for (auto _ : state) benchmark::DoNotOptimize(buffer.composite_image(glm::vec3(1.0f), 1));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kScreen.area()));
}
BENCHMARK(BM_CompositeImage)->ArgName("load")->Arg(50)->Arg(90)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace habuffer::bench
