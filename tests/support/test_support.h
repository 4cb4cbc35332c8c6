// Helpers shared by the test files: buffers, streams and the exact per-pixel
// lists that SPEC invariant 3 compares against.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include <glm/common.hpp>

#include "habuffer/fragment_streams.h"
#include "habuffer/techniques/ha/ha_buffer.h"
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

// A scene for draw-order tests: a coherent stream (several surfaces per
// pixel), and on every third pixel three fragments at one depth with
// different colours (ties the data word breaks) and an exact duplicate.
inline std::vector<Fragment> draw_order_scene(Extent screen, std::size_t count, std::uint64_t seed) {
  std::vector<Fragment> f = stream(screen, StreamKind::Coherent, count, seed);
  SplitMix64 rng(seed + 101);
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = (y % 3); x < screen.x; x += 3) {
      const float t = static_cast<float>(rng.below(1u << 16)) * 0x1.0p-16f;
      for (std::uint32_t k = 0; k < 3; ++k)
        f.push_back({x, y, t, static_cast<std::uint32_t>(rng.next() & 0xFFFFFF00u) | (60u + 60u * k)});
      f.push_back(f[rng.below(f.size())]);  // a duplicate of an earlier fragment (any pixel)
    }
  return shuffled(std::move(f), seed + 7);
}

// Two float images equal bit for bit (signed zeros and NaN payloads included).
inline bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

// How far an approximate technique's image may move when the draw order of
// `frags` is reversed, per pixel and channel (docs/spec-notes.md, "Draw
// order"). wboit: its accumulators are sums and a product, order-free but
// for float rounding: 8 n 2^-24 for a pixel of n valid fragments (while the
// accumulated weight stays below the resolve's 5e4 clamp). blend: the
// colour is a convex combination of the fragments' colours with weights
// a_i prod_(j drawn after i) (1 - a_j), which total 1 - T in any order, so a
// channel moves by at most (1 - T)(c_max - c_min) over the pixel's
// fragments, plus the same rounding; alpha (1 - T) only by rounding.
inline std::vector<glm::vec4> reversal_bound(Technique t, std::span<const Fragment> frags, Extent screen) {
  struct Pixel {
    std::uint32_t n = 0;
    double transmittance = 1.0;
    glm::dvec3 lo{1.0}, hi{0.0};
  };
  std::vector<Pixel> px(screen.area());
  for (const Fragment& f : frags) {
    if (!RecordLayout::depth_valid(f.depth)) continue;
    Pixel& p = px[f.x + std::size_t{f.y} * screen.x];
    ++p.n;
    p.transmittance *= 1.0 - static_cast<double>(f.rgba & 255u) / 255.0;
    const glm::dvec3 c((f.rgba >> 24) / 255.0, ((f.rgba >> 16) & 255u) / 255.0, ((f.rgba >> 8) & 255u) / 255.0);
    p.lo = glm::min(p.lo, c);
    p.hi = glm::max(p.hi, c);
  }
  std::vector<glm::vec4> bound(screen.area());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const double rounding = 8.0 * px[i].n * 0x1.0p-24;
    glm::dvec3 colour(rounding);
    if (t == Technique::Blend && px[i].n > 0) colour += (1.0 - px[i].transmittance) * (px[i].hi - px[i].lo);
    bound[i] = glm::vec4(glm::vec3(colour), static_cast<float>(rounding));
  }
  return bound;
}

// Whether every channel of `a` and `b` differs by at most `bound` (per pixel).
inline bool within_bound(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b,
                         const std::vector<glm::vec4>& bound) {
  if (a.size() != b.size() || a.size() != bound.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 4; ++c)
      if (!(std::abs(a[i][c] - b[i][c]) <= bound[i][c])) return false;
  return true;
}

// A stream whose fragments cover random samples of S: whole pixels (0 or
// every bit), edges (a few bits), and some masks with bits beyond S alone.
inline std::vector<Fragment> covered_stream(Extent screen, std::size_t count, std::uint64_t seed, std::uint32_t samples,
                                            StreamKind kind = StreamKind::Coherent) {
  std::vector<Fragment> frags = stream(screen, kind, count, seed);
  SplitMix64 rng(seed * 977 + 5);
  for (Fragment& f : frags) {
    switch (rng.below(8)) {
      case 0: f.coverage = 0; break;
      case 1: f.coverage = (1u << samples) - 1u; break;
      case 2: f.coverage = 1u << (samples + rng.below(4)); break;  // no sample of the S: invalid
      default: f.coverage = static_cast<std::uint32_t>(rng.next() & ((1u << (2 * samples)) - 1u)); break;
    }
  }
  return frags;
}

}  // namespace habuffer::test
