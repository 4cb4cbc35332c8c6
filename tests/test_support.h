// Helpers shared by the test files: buffers, streams and the exact per-pixel
// lists that SPEC invariant 3 compares against.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/ha_buffer.h"
#include "habuffer/random.h"
#include "habuffer/technique.h"

namespace habuffer::test {

inline BufferConfig config(Extent screen, Extent table, Layout layout = Layout::L64, std::uint32_t age_bits = 8,
                           std::uint32_t block = 8) {
  BufferConfig c;
  c.screen = screen;
  c.table = table;
  c.layout = layout;
  c.age_bits = age_bits;
  c.block = block;
  return c;
}

// Technique `t` over `screen` (the HA-buffer's table the screen itself).
inline TechniqueConfig technique_config(Technique t, Extent screen, Layout layout = Layout::L64,
                                        std::uint32_t age_bits = 8) {
  TechniqueConfig c;
  c.technique = t;
  c.buffer = config(screen, screen, layout, age_bits);
  return c;
}

// `count` fragments at random pixels, depths on the 2^-20 grid (depth
// quantization cannot reorder them), random colours with alpha in
// [min_alpha, 255].
inline std::vector<Fragment> grid_stream(Extent screen, std::size_t count, std::uint64_t seed, std::uint32_t min_alpha) {
  SplitMix64 rng(seed);
  std::vector<Fragment> f;
  f.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto x = static_cast<std::uint32_t>(rng.below(screen.x)), y = static_cast<std::uint32_t>(rng.below(screen.y));
    const float t = static_cast<float>(rng.below(1u << 20)) * 0x1.0p-20f;
    const auto colour = static_cast<std::uint32_t>(rng.next() & 0xFFFFFF00u);
    const auto alpha = static_cast<std::uint32_t>(min_alpha + rng.below(256 - min_alpha));
    f.push_back({x, y, t, colour | alpha});
  }
  return f;
}

// The largest absolute difference over the RGBA of two images of one size.
inline float largest_difference(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  float most = 0.0f;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    for (int c = 0; c < 4; ++c) most = std::max(most, std::abs(a[i][c] - b[i][c]));
  return a.size() == b.size() ? most : std::numeric_limits<float>::infinity();
}

inline HaBuffer make_buffer(const BufferConfig& c, std::uint64_t seed = 1,
                            OffsetGenerator gen = OffsetGenerator::Random) {
  return HaBuffer(c, OffsetSequence::make(gen, c.table_or_screen(), c.record_layout().max_age(), seed));
}

// Exact expected lists: per pixel, the distinct (code, data) pairs of its
// valid fragments, nearest first (record order: code then data, descending).
using ExactLists = std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<ListEntry>>;

inline ExactLists exact_lists(const std::vector<Fragment>& frags, const RecordLayout& layout) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::set<std::pair<std::uint32_t, std::uint32_t>>> sets;
  for (const Fragment& f : frags)
    if (RecordLayout::depth_valid(f.depth))
      sets[{f.x, f.y}].insert({layout.depth_code(f.depth), layout.has_data() ? f.rgba : 0u});
  ExactLists out;
  for (const auto& [p, s] : sets) {
    auto& v = out[p];
    for (auto it = s.rbegin(); it != s.rend(); ++it) v.push_back({0, it->first, it->second});
  }
  return out;
}

// Lists of any technique (the HA-buffer's by traversal), ages dropped so
// they compare with exact_lists.
inline ExactLists traversed_lists(const FragmentBuffer& b) {
  ExactLists out;
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < b.screen().y; ++y)
    for (std::uint32_t x = 0; x < b.screen().x; ++x) {
      b.list(x, y, list);
      if (list.empty()) continue;
      auto& v = out[{x, y}];
      for (ListEntry e : list) v.push_back({0, e.code, e.data});
    }
  return out;
}

// The most fragments any pixel of `screen` receives.
inline std::uint32_t depth_complexity(std::span<const Fragment> frags, Extent screen) {
  std::vector<std::uint32_t> n(screen.area(), 0);
  for (const Fragment& f : frags) ++n[f.x + std::size_t{f.y} * screen.x];
  return *std::max_element(n.begin(), n.end());
}

inline std::vector<std::uint64_t> table_words(const HaBuffer& b) {
  std::vector<std::uint64_t> t(b.slot_count());
  for (std::uint64_t s = 0; s < t.size(); ++s) t[s] = b.slot(s);
  return t;
}

inline std::vector<Fragment> shuffled(std::vector<Fragment> v, std::uint64_t seed) {
  SplitMix64 rng(seed);
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng.below(i)]);
  return v;
}

inline std::vector<Fragment> stream(Extent screen, StreamKind kind, std::uint64_t count, std::uint64_t seed) {
  StreamOptions o;
  o.kind = kind;
  o.count = count;
  o.seed = seed;
  return make_stream(screen, o);
}

}  // namespace habuffer::test
