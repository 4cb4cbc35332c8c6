#include "habuffer/harness/floors.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <chrono>
#include <stdexcept>

#include "habuffer/hash_kernel.h"
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
  if (gl_) return {gl_->atomic_ms(), gl_->blend_ms(), 0.0};
  const Extent screen = capture_.reference.size;
  Floors f{cpu_atomic_floor_ms(capture_.stream, screen, threads_), cpu_blend_floor_ms(capture_, screen, threads_), 0.0};
  (void)exact_.image(capture_.stream, screen, capture_.backgrounds, threads_);  // steady state: buckets kept
  const auto t0 = Clock::now();
  (void)exact_.image(capture_.stream, screen, capture_.backgrounds, threads_);
  f.exact_ms = ms_since(t0);
  return f;
}

std::vector<glm::vec4> ExactFloor::image(std::span<const Fragment> fragments, Extent screen,
                                         std::span<const glm::vec3> backgrounds, std::uint32_t threads) {
  if (backgrounds.size() != screen.area())
    throw std::invalid_argument("exact floor: " + std::to_string(backgrounds.size()) + " backgrounds for screen " +
                                screen.str());
  if (fragments.size() >= UINT32_MAX)
    throw std::invalid_argument("exact floor: " + std::to_string(fragments.size()) + " fragments, at most 2^32 - 2");
  // The record packing and blend every technique shares (a kernel with no buffers).
  HashKernel<std::uint64_t, false> k(KernelParams{}, nullptr, nullptr, nullptr);
  const auto record = [&](const Fragment& f) { return std::uint64_t{k.ha_depth_code(f.depth)} << 32 | f.rgba; };
  begin_.assign(screen.area() + 2, 0);
  std::size_t n = 0;
  for (const Fragment& f : fragments)
    if (k.ha_depth_valid(f.depth)) {
      check_pixel(f.x, f.y, screen);
      ++begin_[f.x + std::size_t{f.y} * screen.x + 2];
      ++n;
    }
  for (std::size_t i = 2; i < begin_.size(); ++i) begin_[i] += begin_[i - 1];
  records_.resize(n);
  for (const Fragment& f : fragments)
    if (k.ha_depth_valid(f.depth)) records_[begin_[f.x + std::size_t{f.y} * screen.x + 1]++] = record(f);
  std::vector<glm::vec4> image(screen.area());
  const std::uint32_t parts = resolve_threads(threads, screen.area());
  fork_join(parts, [&](std::uint32_t part) {
    HashKernel<std::uint64_t, false> blend = k;
    const std::size_t first = screen.area() * part / parts, last = screen.area() * (part + 1) / parts;
    for (std::size_t p = first; p < last; ++p) {
      const auto list = std::span<std::uint64_t>(records_).subspan(begin_[p], begin_[p + 1] - begin_[p]);
      std::sort(list.begin(), list.end(), std::greater<>());
      glm::vec4 c(0.0f);
      for (std::size_t i = 0; i < list.size(); ++i)
        if (i == 0 || list[i] != list[i - 1]) c = blend.ha_blend_under(c, blend.ha_unpack_rgba(static_cast<std::uint32_t>(list[i])));
      image[p] = blend.ha_finish(c, backgrounds[p]);
    }
  });
  return image;
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
