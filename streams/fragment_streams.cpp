#include "habuffer/fragment_streams.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/random.h"

namespace habuffer {
namespace {

std::uint32_t random_colour(SplitMix64& rng, const StreamOptions& o) {
  const auto rgb = static_cast<std::uint32_t>(rng.next() & 0xFFFFFF00u);
  const auto alpha = o.alpha_min + static_cast<std::uint32_t>(rng.below(o.alpha_max - o.alpha_min + 1));
  return rgb | alpha;
}

void emit_random(Extent screen, const StreamOptions& o, SplitMix64& rng, std::vector<Fragment>& out) {
  while (out.size() < o.count) {
    const auto x = static_cast<std::uint32_t>(rng.below(screen.x));
    const auto y = static_cast<std::uint32_t>(rng.below(screen.y));
    out.push_back({x, y, rng.unit_float(), random_colour(rng, o)});
  }
}

// A planar primitive: depth varies linearly over the bounding box. Triangles
// keep the pixels on one side of the box's diagonal.
void emit_primitive(Extent screen, const StreamOptions& o, SplitMix64& rng, std::vector<Fragment>& out) {
  auto side = [&] {
    return o.min_side + static_cast<std::uint32_t>(rng.below(o.max_side - o.min_side + 1));
  };
  const std::uint32_t w = std::min(side(), screen.x), h = std::min(side(), screen.y);
  const auto x0 = static_cast<std::uint32_t>(rng.below(screen.x - w + 1));
  const auto y0 = static_cast<std::uint32_t>(rng.below(screen.y - h + 1));
  const bool triangle = (rng.next() & 1) != 0;
  const float z0 = rng.unit_float() * 0.9f + 0.05f;
  const float dzx = (rng.unit_float() - 0.5f) * 0.04f / static_cast<float>(w);
  const float dzy = (rng.unit_float() - 0.5f) * 0.04f / static_cast<float>(h);
  const std::uint32_t colour = random_colour(rng, o);
  for (std::uint32_t j = 0; j < h && out.size() < o.count; ++j) {
    const std::uint32_t span = triangle ? std::max<std::uint32_t>(1, w - (j * w) / h) : w;
    for (std::uint32_t i = 0; i < span && out.size() < o.count; ++i) {
      const float z = z0 + dzx * static_cast<float>(i) + dzy * static_cast<float>(j);
      out.push_back({x0 + i, y0 + j, std::clamp(z, 0.0f, 1.0f), colour});
    }
  }
}

}  // namespace

std::vector<Fragment> make_stream(Extent screen, const StreamOptions& o) {
  if (screen.area() == 0) throw std::invalid_argument("stream screen is empty");
  if (o.min_side == 0 || o.min_side > o.max_side) throw std::invalid_argument("stream primitive sides need 1 <= min <= max");
  if (o.alpha_min > o.alpha_max || o.alpha_max > 255) throw std::invalid_argument("stream alpha needs min <= max <= 255");
  SplitMix64 rng(o.seed ^ 0x3C6EF372FE94F82Bull);
  std::vector<Fragment> out;
  out.reserve(o.count);
  if (o.kind == StreamKind::Random) {
    emit_random(screen, o, rng, out);
  } else {
    while (out.size() < o.count) emit_primitive(screen, o, rng, out);
  }
  return out;
}

Extent table_for_load(Extent screen, std::uint64_t fragments, double load) {
  if (!(load > 0.0)) throw std::invalid_argument("load must be positive");
  const double scale = std::sqrt(static_cast<double>(fragments) / load / static_cast<double>(screen.area()));
  auto side = [&](std::uint32_t v) {
    return std::max(v, static_cast<std::uint32_t>(std::ceil(static_cast<double>(v) * scale)));
  };
  return {side(screen.x), side(screen.y)};
}

StreamKind parse_stream_kind(const std::string& name) {
  if (name == "random") return StreamKind::Random;
  if (name == "coherent") return StreamKind::Coherent;
  throw std::invalid_argument("unknown stream '" + name + "' (expected random or coherent)");
}

std::string to_string(StreamKind kind) { return kind == StreamKind::Random ? "random" : "coherent"; }

}  // namespace habuffer
