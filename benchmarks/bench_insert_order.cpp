// The HA-buffer's two insertion orders (issue 26) on one stream, interleaved
// by google-benchmark's --benchmark_enable_random_interleaving: arrival order
// (each fragment probes from age 1) and pixel order (bucketed by pixel,
// nearest first, jump-started; techniques/ha/cpu/src/pixel_order.h), on 2^20 fragments over
// 1024x1024 (about one per pixel, the core issue's stream), 512x512 (4) and
// 256x256 (16, the depth of engine); pixel
// order 2 interleaves pixels (latency hiding). Tables of 2^20 fragments at
// load 0.5 take 16 MiB, beyond this machine's caches.
// items_per_second = fragments per second; both give the same table.
#include <benchmark/benchmark.h>

#include "bench_common.h"

namespace habuffer::bench {
namespace {

void BM_InsertOrder(benchmark::State& state) {
  const bool pixel = state.range(0) != 0;  // 1: pixel order, 2: pixel order interleaved
  const auto side = static_cast<std::uint32_t>(state.range(1));
  const Extent screen{side, side};
  const double load = static_cast<double>(state.range(2)) / 100.0;
  const auto& frags = stream(StreamKind::Coherent, screen);
  HaBuffer buffer = buffer_for_load(screen, frags.size(), load);
  InsertOptions options;
  options.order = pixel ? InsertOrder::Pixel : InsertOrder::Arrival;
  options.threads = static_cast<std::uint32_t>(state.range(3));
  if (pixel) options.interleave = state.range(0) == 2;
  Counters counters;
  for (auto _ : state) {
    state.PauseTiming();
    buffer.clear();
    state.ResumeTiming();
    counters = buffer.insert(frags, options);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * frags.size()));
  state.counters["load"] = static_cast<double>(counters.stored()) / static_cast<double>(buffer.slot_count());
  state.counters["failed"] = static_cast<double>(counters.failures());
}

BENCHMARK(BM_InsertOrder)
    ->ArgNames({"pixel", "side", "load", "threads"})
    ->ArgsProduct({{0, 1, 2}, {1024, 512, 362, 256}, {50, 80}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace habuffer::bench
