#include "habuffer/harness/floors.h"

#include <atomic>
#include <chrono>
#include <stdexcept>

#include "habuffer/lossless_build.h"
#include "habuffer/parallel.h"

namespace habuffer::harness {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double cpu_blend_floor_ms(const ExactCapture& c, Extent screen, std::uint32_t threads) {
  TechniqueConfig config;
  config.technique = Technique::Blend;
  config.buffer.screen = screen;
  config.buffer.table = screen;
  const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(config, OffsetSource{});
  InsertOptions o;
  o.threads = threads;
  const auto t0 = Clock::now();
  (void)b->insert(c.stream, o);
  return ms_since(t0);
}

}  // namespace

FloorMeter::FloorMeter(const Workload& workload, const ExactCapture& capture, RenderPath path, std::uint32_t threads)
    : capture_(capture), threads_(threads) {
  if (path != RenderPath::Gl) return;
  if (workload.scene() == nullptr) throw std::invalid_argument("a fragment stream has no GL floor: use the CPU path");
  gl_ = std::make_unique<GlFloors>(*workload.scene(), workload.size());
}

FloorMeter::~FloorMeter() = default;

Floors FloorMeter::measure() {
  if (gl_) return {gl_->atomic_ms(), gl_->blend_ms()};
  const Extent screen = capture_.reference.size;
  return {cpu_atomic_floor_ms(capture_.stream, screen, threads_), cpu_blend_floor_ms(capture_, screen, threads_)};
}

double cpu_atomic_floor_ms(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads) {
  std::vector<std::uint32_t> counts(screen.area(), 0);
  const std::uint32_t n = resolve_threads(threads);
  const auto t0 = Clock::now();
  fork_join(n, [&](std::uint32_t t) {
    const std::size_t begin = fragments.size() * t / n, end = fragments.size() * (t + 1) / n;
    for (std::size_t i = begin; i < end; ++i)
      std::atomic_ref<std::uint32_t>(counts[fragments[i].x + std::size_t{fragments[i].y} * screen.x])
          .fetch_add(1, std::memory_order_relaxed);
  });
  return ms_since(t0);
}

}  // namespace habuffer::harness
