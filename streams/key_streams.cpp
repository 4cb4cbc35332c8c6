#include "habuffer/key_streams.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <tuple>

namespace habuffer::spatial {
namespace {

bool row_major_less(const glm::uvec3& a, const glm::uvec3& b) {
  return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x);
}

// Bits of x, y, z interleaved (21 bits each).
std::uint64_t morton(glm::uvec3 k) {
  const auto spread = [](std::uint64_t v) {
    v &= 0x1FFFFF;
    v = (v | v << 32) & 0x1F00000000FFFFull;
    v = (v | v << 16) & 0x1F0000FF0000FFull;
    v = (v | v << 8) & 0x100F00F00F00F00Full;
    v = (v | v << 4) & 0x10C30C30C30C30C3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  return spread(k.x) | spread(k.y) << 1 | spread(k.z) << 2;
}

}  // namespace

std::string to_string(KeySet set) {
  switch (set) {
    case KeySet::SparseImage: return "sparse-image";
    case KeySet::VoxelShell: return "voxel-shell";
    case KeySet::Random: return "random";
  }
  return "?";
}

std::string to_string(KeyOrder order) {
  switch (order) {
    case KeyOrder::RowMajor: return "row-major";
    case KeyOrder::Morton: return "morton";
    case KeyOrder::RandomWalk: return "random-walk";
    case KeyOrder::Shuffled: return "shuffled";
  }
  return "?";
}

std::optional<KeySet> parse_key_set(const std::string& text) {
  for (const KeySet s : {KeySet::SparseImage, KeySet::VoxelShell, KeySet::Random})
    if (to_string(s) == text) return s;
  return std::nullopt;
}

std::optional<KeyOrder> parse_key_order(const std::string& text) {
  for (const KeyOrder o : {KeyOrder::RowMajor, KeyOrder::Morton, KeyOrder::RandomWalk, KeyOrder::Shuffled})
    if (to_string(o) == text) return o;
  return std::nullopt;
}

void KeySetOptions::validate() const {
  (void)FoldedDomain(domain);
  const std::uint64_t cells = std::uint64_t{domain.x} * domain.y * domain.z;
  if (cells > (std::uint64_t{1} << 34))
    throw std::invalid_argument("key set: domain " + domain.str() + " has more than 2^34 points");
  if (set == KeySet::SparseImage && !(coverage > 0.0 && coverage <= 0.9))
    throw std::invalid_argument("key set: coverage " + std::to_string(coverage) + " outside (0, 0.9]");
  if (set == KeySet::VoxelShell && (domain.x != domain.y || domain.y != domain.z || domain.x < 4))
    throw std::invalid_argument("key set: a voxel shell needs a cube domain of side at least 4, not " + domain.str());
  if (set == KeySet::Random && (count == 0 || count > cells / 2))
    throw std::invalid_argument("key set: " + std::to_string(count) + " random keys in " + domain.str() +
                                " (1 .. half the domain's points)");
}

std::vector<glm::uvec3> make_keys(const KeySetOptions& o) {
  o.validate();
  std::mt19937_64 rng(o.seed);
  const Domain d = o.domain;
  std::vector<glm::uvec3> keys;
  if (o.set == KeySet::SparseImage) {
    // Discs (per z layer) until the coverage is reached, marked in a bitmap.
    const std::uint64_t layer = std::uint64_t{d.x} * d.y;
    std::vector<bool> on(layer * d.z, false);
    const double target = o.coverage * static_cast<double>(on.size());
    const double r_max = std::max(2.0, 0.04 * std::min(d.x, d.y));
    std::uint64_t covered = 0;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    while (static_cast<double>(covered) < target) {
      const double cx = unit(rng) * d.x, cy = unit(rng) * d.y, r = 1.0 + unit(rng) * r_max;
      const auto z = static_cast<std::uint32_t>(rng() % d.z);
      // Pixel centres (x + 0.5, y + 0.5) inside the disc, clipped to the
      // domain in signed arithmetic: a disc near the border has spans that
      // start or end off the domain (a negative column is no column).
      const auto y0 = static_cast<std::int64_t>(std::max(0.0, cy - r));
      const auto y1 = static_cast<std::int64_t>(std::min<double>(d.y - 1, cy + r));
      for (std::int64_t y = y0; y <= y1; ++y) {
        const double dy = static_cast<double>(y) + 0.5 - cy, half = std::sqrt(std::max(0.0, r * r - dy * dy));
        const auto x0 = static_cast<std::int64_t>(std::max(0.0, std::ceil(cx - half - 0.5)));
        const auto x1 = std::min<std::int64_t>(d.x - 1, static_cast<std::int64_t>(std::floor(cx + half - 0.5)));
        for (std::int64_t x = x0; x <= x1; ++x) {
          const auto i = static_cast<std::uint64_t>(x) + std::uint64_t{d.x} * static_cast<std::uint64_t>(y) + layer * z;
          if (!on[i]) {
            on[i] = true;
            ++covered;
          }
        }
      }
    }
    keys.reserve(covered);
    for (std::uint64_t i = 0; i < on.size(); ++i)
      if (on[i])
        keys.emplace_back(static_cast<std::uint32_t>(i % d.x), static_cast<std::uint32_t>(i / d.x % d.y),
                          static_cast<std::uint32_t>(i / layer));
  } else if (o.set == KeySet::VoxelShell) {
    const double c = d.x / 2.0, r = 0.4 * d.x;
    for (std::uint32_t z = 0; z < d.z; ++z)
      for (std::uint32_t y = 0; y < d.y; ++y)
        for (std::uint32_t x = 0; x < d.x; ++x) {
          const double dx = x + 0.5 - c, dy = y + 0.5 - c, dz = z + 0.5 - c;
          if (std::abs(std::sqrt(dx * dx + dy * dy + dz * dz) - r) <= 0.5) keys.emplace_back(x, y, z);
        }
  } else {
    std::vector<glm::uvec3> drawn;
    while (keys.size() < o.count) {
      drawn.clear();
      for (std::uint64_t i = keys.size(); i < o.count; ++i)
        drawn.emplace_back(static_cast<std::uint32_t>(rng() % d.x), static_cast<std::uint32_t>(rng() % d.y),
                           static_cast<std::uint32_t>(rng() % d.z));
      keys.insert(keys.end(), drawn.begin(), drawn.end());
      std::sort(keys.begin(), keys.end(), row_major_less);
      keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    }
  }
  return keys;
}

std::vector<glm::uvec3> absent_keys(const std::vector<glm::uvec3>& keys, Domain d, std::uint64_t count,
                                    std::uint64_t seed) {
  const std::uint64_t cells = std::uint64_t{d.x} * d.y * d.z;
  if (cells - keys.size() < 2 * count)
    throw std::invalid_argument("absent keys: " + std::to_string(count) + " wanted, the domain " + d.str() +
                                " has " + std::to_string(cells - keys.size()) + " free points");
  std::mt19937_64 rng(seed);
  std::vector<glm::uvec3> out;
  out.reserve(count);
  while (out.size() < count) {
    const glm::uvec3 k(static_cast<std::uint32_t>(rng() % d.x), static_cast<std::uint32_t>(rng() % d.y),
                       static_cast<std::uint32_t>(rng() % d.z));
    if (!std::binary_search(keys.begin(), keys.end(), k, row_major_less)) out.push_back(k);
  }
  return out;
}

std::vector<glm::uvec3> ordered(std::vector<glm::uvec3> keys, KeyOrder order, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  switch (order) {
    case KeyOrder::RowMajor: std::sort(keys.begin(), keys.end(), row_major_less); break;
    case KeyOrder::Morton:
      std::sort(keys.begin(), keys.end(), [](glm::uvec3 a, glm::uvec3 b) { return morton(a) < morton(b); });
      break;
    case KeyOrder::Shuffled: std::shuffle(keys.begin(), keys.end(), rng); break;
    case KeyOrder::RandomWalk: {
      // Morton order cut into runs of 64 keys; the runs visited in a walk
      // that moves to one of the next 16 runs (a random one not yet
      // visited), or jumps when none is left: coherent within a run and
      // between nearby runs, not sorted.
      std::sort(keys.begin(), keys.end(), [](glm::uvec3 a, glm::uvec3 b) { return morton(a) < morton(b); });
      const std::size_t runs = (keys.size() + 63) / 64;
      std::vector<bool> seen(runs, false);
      std::vector<glm::uvec3> out;
      out.reserve(keys.size());
      std::size_t at = 0, next_unseen = 0;
      for (std::size_t visited = 0; visited < runs; ++visited) {
        seen[at] = true;
        for (std::size_t i = at * 64; i < std::min(keys.size(), at * 64 + 64); ++i) out.push_back(keys[i]);
        std::size_t step = 0;
        for (int tries = 0; tries < 8 && step == 0; ++tries) {
          const std::size_t c = at + 1 + rng() % 16;
          if (c < runs && !seen[c]) step = c;
        }
        while (next_unseen < runs && seen[next_unseen]) ++next_unseen;
        at = step != 0 ? step : next_unseen;
        if (at >= runs) break;
      }
      return out;
    }
  }
  return keys;
}

}  // namespace habuffer::spatial
