// Streams and buffers shared by the benchmarks, made once per process.
#pragma once

#include <map>
#include <tuple>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/techniques/ha/ha_buffer.h"

namespace habuffer::bench {

// The stream of the core issue's measurements: 2^20 fragments on a 1024x1024 screen.
inline constexpr Extent kScreen{1024, 1024};
inline constexpr std::uint64_t kFragments = std::uint64_t{1} << 20;

inline const std::vector<Fragment>& stream(StreamKind kind, Extent screen = kScreen, std::uint64_t count = kFragments) {
  static std::map<std::tuple<int, std::uint32_t, std::uint32_t, std::uint64_t>, std::vector<Fragment>> cache;
  auto key = std::make_tuple(static_cast<int>(kind), screen.x, screen.y, count);
  auto it = cache.find(key);
  if (it == cache.end()) {
    StreamOptions o;
    o.kind = kind;
    o.count = count;
    o.seed = 42;
    it = cache.emplace(key, make_stream(screen, o)).first;
  }
  return it->second;
}

inline HaBuffer buffer_for_load(Extent screen, std::uint64_t fragments, double load, Layout layout = Layout::L64) {
  BufferConfig c;
  c.screen = screen;
  c.table = table_for_load(screen, fragments, load);
  c.layout = layout;
  return HaBuffer(c, OffsetSequence::random(c.table, c.record_layout().max_age(), 7));
}

// The one EGL context of the benchmarks (made once, made current for each caller).
inline gl::EglContext& gl_bench_context() {
  static gl::EglContext context;
  context.make_current();
  return context;
}

}  // namespace habuffer::bench
