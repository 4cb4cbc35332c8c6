// Offset generation time: farthest-point on tables up to 4096x4096.
#include <benchmark/benchmark.h>

#include "habuffer/offset_sequence.h"

namespace habuffer::bench {
namespace {

void BM_FarthestOffsets(benchmark::State& state) {
  const auto side = static_cast<std::uint32_t>(state.range(0));
  std::uint64_t seed = 1;
  for (auto _ : state) benchmark::DoNotOptimize(OffsetSequence::farthest({side, side}, 255, seed++));
}
BENCHMARK(BM_FarthestOffsets)->ArgName("table")->Arg(1024)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond);

void BM_RandomOffsets(benchmark::State& state) {
  const auto side = static_cast<std::uint32_t>(state.range(0));
  std::uint64_t seed = 1;
  for (auto _ : state) benchmark::DoNotOptimize(OffsetSequence::random({side, side}, 255, seed++));
}
BENCHMARK(BM_RandomOffsets)->ArgName("table")->Arg(4096)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace habuffer::bench
