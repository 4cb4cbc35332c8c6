#include "habuffer/fragment_streams.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/option_rules.h"
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

void emit_stacked(Extent screen, const StreamOptions& o, SplitMix64& rng, std::vector<Fragment>& out) {
  const std::uint32_t w = std::min(o.quad_side, screen.x), h = std::min(o.quad_side, screen.y);
  const double cx = (screen.x - w) / 2.0, cy = (screen.y - h) / 2.0;
  while (out.size() < o.count) {
    // Uniform position, pulled towards the centre by (1 - spread).
    const double ux = static_cast<double>(rng.below(screen.x - w + 1));
    const double uy = static_cast<double>(rng.below(screen.y - h + 1));
    const auto x0 = static_cast<std::uint32_t>(std::lround(cx + (ux - cx) * o.spread));
    const auto y0 = static_cast<std::uint32_t>(std::lround(cy + (uy - cy) * o.spread));
    const float z = rng.unit_float();
    const std::uint32_t colour = random_colour(rng, o);
    for (std::uint32_t j = 0; j < h && out.size() < o.count; ++j)
      for (std::uint32_t i = 0; i < w && out.size() < o.count; ++i) out.push_back({x0 + i, y0 + j, z, colour});
  }
}

void emit_hot(Extent screen, const StreamOptions& o, SplitMix64& rng, std::vector<Fragment>& out) {
  const std::uint64_t hot_total = std::min<std::uint64_t>(o.count, std::uint64_t{o.hot_pixels} * o.hot_depth);
  for (std::uint32_t k = 0; out.size() < hot_total; ++k) {
    const auto x = static_cast<std::uint32_t>(rng.below(screen.x)), y = static_cast<std::uint32_t>(rng.below(screen.y));
    for (std::uint32_t d = 0; d < o.hot_depth && out.size() < hot_total; ++d)
      out.push_back({x, y, rng.unit_float(), random_colour(rng, o)});
  }
  emit_random(screen, o, rng, out);
}

}  // namespace

std::vector<Fragment> make_stream(Extent screen, const StreamOptions& o) {
  if (screen.area() == 0) throw std::invalid_argument("stream screen is empty");
  if (o.min_side == 0 || o.min_side > o.max_side) throw std::invalid_argument("stream primitive sides need 1 <= min <= max");
  if (o.alpha_min > o.alpha_max || o.alpha_max > 255) throw std::invalid_argument("stream alpha needs min <= max <= 255");
  if (!(o.spread >= 0.0 && o.spread <= 1.0)) throw std::invalid_argument("stream spread must be in [0, 1]");
  if (o.quad_side == 0) throw std::invalid_argument("stacked quads need a positive side");
  SplitMix64 rng(o.seed ^ 0x3C6EF372FE94F82Bull);
  std::vector<Fragment> out;
  out.reserve(o.count);
  switch (o.kind) {
    case StreamKind::Random: emit_random(screen, o, rng, out); break;
    case StreamKind::Coherent:
      while (out.size() < o.count) emit_primitive(screen, o, rng, out);
      break;
    case StreamKind::Stacked: emit_stacked(screen, o, rng, out); break;
    case StreamKind::Hot: emit_hot(screen, o, rng, out); break;
  }
  return out;
}


StreamKind parse_stream_kind(const std::string& name) {
  if (name == "random") return StreamKind::Random;
  if (name == "coherent") return StreamKind::Coherent;
  if (name == "stacked") return StreamKind::Stacked;
  if (name == "hot") return StreamKind::Hot;
  throw std::invalid_argument("unknown stream '" + name + "' (expected random, coherent, stacked or hot)");
}

std::string to_string(StreamKind kind) {
  switch (kind) {
    case StreamKind::Random: return "random";
    case StreamKind::Coherent: return "coherent";
    case StreamKind::Stacked: return "stacked";
    case StreamKind::Hot: return "hot";
  }
  return "?";
}

std::vector<Fragment> layered_stream(Extent screen, std::uint32_t layers, std::uint32_t seed) {
  if (screen.area() == 0) throw std::invalid_argument("layered stream: empty screen " + screen.str());
  if (std::uint64_t{layers} * screen.area() > (std::uint64_t{1} << 31))
    throw std::invalid_argument("layered stream: " + std::to_string(layers) + " layers of " + screen.str() +
                                " exceed 2^31 fragments");
  std::vector<Fragment> f;
  f.reserve(std::uint64_t{layers} * screen.area());
  for (std::uint32_t l = 0; l < layers; ++l)
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x) {
        const std::uint32_t k = (l + x + y + seed) % layers;
        const std::uint32_t rgba = (x * 73856093u) ^ (y * 19349663u) ^ (l * 83492791u) ^ seed;
        f.push_back({x, y, (static_cast<float>(k) + 0.5f) / static_cast<float>(layers), rgba | 0x80u});
      }
  return f;
}

}  // namespace habuffer
