// Greedy farthest-point offsets on the Hx x Hy torus.
//
// A distance field holds, for every slot, the squared toroidal distance to the
// nearest offset chosen so far. The next offset is the slot where it is
// largest. Two facts keep this fast on a 4096x4096 table:
// - a new offset q can only lower the field where |x - q|^2 < d_max (every
//   slot is already within d_max of some offset), so only a disc around q is
//   updated, and those discs shrink as offsets accumulate;
// - the maximum is kept per 32x32 tile, so picking the argmax scans tiles, and
//   only tiles a disc touched are rescanned.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/offset_sequence.h"
#include "habuffer/random.h"

namespace habuffer {
namespace {

constexpr std::uint32_t kTile = 32;

class DistanceField {
 public:
  explicit DistanceField(Extent table)
      : table_(table),
        tiles_x_((table.x + kTile - 1) / kTile),
        tiles_y_((table.y + kTile - 1) / kTile),
        d2_(table.area(), UINT32_MAX),
        tile_best_(std::size_t{tiles_x_} * tiles_y_) {}

  // Lowers the field around q and refreshes the tiles it touched.
  void add(glm::uvec2 q) {
    const std::uint64_t limit = max_d2();  // strict bound: only d2 < limit can improve
    const std::uint32_t ry = axis_radius(limit, table_.y);
    for (std::int64_t dy = -std::int64_t{ry}; dy <= std::int64_t{ry}; ++dy) {
      if (2 * std::uint64_t{ry} + 1 > table_.y && dy >= std::int64_t{table_.y} - std::int64_t{ry}) break;
      const std::uint32_t y = wrap(std::int64_t{q.y} + dy, table_.y);
      const std::uint64_t ady = axis_dist(y, q.y, table_.y);
      const std::uint64_t dy2 = ady * ady;
      if (dy2 >= limit) continue;
      const std::uint32_t rx = axis_radius(limit - dy2, table_.x);
      update_row(y, q.x, rx, dy2);
    }
    refresh_tiles(q, axis_radius(limit, table_.x), ry);
  }

  // The slot with the largest distance (ties: smallest slot index).
  [[nodiscard]] glm::uvec2 argmax() const {
    std::size_t best = 0;
    for (std::size_t t = 1; t < tile_best_.size(); ++t)
      if (better(tile_best_[t], tile_best_[best])) best = t;
    const std::uint64_t s = tile_best_[best].slot;
    return {static_cast<std::uint32_t>(s % table_.x), static_cast<std::uint32_t>(s / table_.x)};
  }

 private:
  struct Best {
    std::uint32_t d2 = 0;
    std::uint64_t slot = UINT64_MAX;
  };

  static bool better(const Best& a, const Best& b) { return a.d2 > b.d2 || (a.d2 == b.d2 && a.slot < b.slot); }

  [[nodiscard]] std::uint64_t max_d2() const {
    std::uint64_t m = 0;
    for (const auto& b : tile_best_) m = std::max<std::uint64_t>(m, b.d2);
    return m == 0 ? UINT64_MAX : m;  // first offset: the whole field is "infinite"
  }

  static std::uint32_t wrap(std::int64_t v, std::uint32_t size) {
    v %= size;
    return static_cast<std::uint32_t>(v < 0 ? v + size : v);
  }
  static std::uint64_t axis_dist(std::uint32_t u, std::uint32_t v, std::uint32_t size) {
    std::uint64_t d = u > v ? u - v : v - u;
    return std::min<std::uint64_t>(d, size - d);
  }
  // Largest r with r^2 < limit, capped at half the axis (beyond it the torus wraps).
  static std::uint32_t axis_radius(std::uint64_t limit, std::uint32_t size) {
    const std::uint64_t cap = size / 2;
    if (limit == UINT64_MAX || limit > cap * cap + cap * 2 + 1) return static_cast<std::uint32_t>(cap);
    auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(limit)));
    while (r * r >= limit) --r;
    while ((r + 1) * (r + 1) < limit) ++r;
    return static_cast<std::uint32_t>(std::min(r, cap));
  }

  void update_row(std::uint32_t y, std::uint32_t qx, std::uint32_t rx, std::uint64_t dy2) {
    std::uint32_t* row = d2_.data() + std::uint64_t{y} * table_.x;
    // With rx = floor(size/2) on an even axis, -rx and +rx are the same column.
    const std::int64_t hi = (2 * std::uint64_t{rx} + 1 > table_.x) ? std::int64_t{table_.x} - rx - 1 : rx;
    for (std::int64_t dx = -std::int64_t{rx}; dx <= hi; ++dx) {
      const std::uint32_t x = wrap(std::int64_t{qx} + dx, table_.x);
      const std::uint64_t adx = axis_dist(x, qx, table_.x);
      const std::uint64_t d2 = adx * adx + dy2;
      if (d2 < row[x]) row[x] = static_cast<std::uint32_t>(d2);
    }
  }

  void refresh_tile(std::uint32_t tx, std::uint32_t ty) {
    Best best;
    const std::uint32_t x1 = std::min(table_.x, (tx + 1) * kTile), y1 = std::min(table_.y, (ty + 1) * kTile);
    for (std::uint32_t y = ty * kTile; y < y1; ++y)
      for (std::uint32_t x = tx * kTile; x < x1; ++x) {
        const std::uint64_t s = x + std::uint64_t{y} * table_.x;
        if (d2_[s] > best.d2) best = {d2_[s], s};
      }
    tile_best_[tx + std::size_t{ty} * tiles_x_] = best;
  }

  void refresh_tiles(glm::uvec2 q, std::uint32_t rx, std::uint32_t ry) {
    auto tile_span = [](std::uint32_t c, std::uint32_t r_, std::uint32_t size, std::uint32_t tiles) {
      // Tiles covering [c - r, c + r] on a torus of `size` cells, as (first, count).
      if (2 * std::uint64_t{r_} + 1 >= size) return std::pair<std::uint32_t, std::uint32_t>{0, tiles};
      const std::uint32_t lo = wrap(std::int64_t{c} - r_, size);
      const std::uint32_t first = lo / kTile;
      const std::uint32_t last_cell = lo + 2 * r_;  // may exceed size: wraps below
      const std::uint32_t count = std::min(tiles, last_cell / kTile - first + 1 + (last_cell >= size ? 1u : 0u));
      return std::pair<std::uint32_t, std::uint32_t>{first, count};
    };
    const auto [fx, nx] = tile_span(q.x, rx, table_.x, tiles_x_);
    const auto [fy, ny] = tile_span(q.y, ry, table_.y, tiles_y_);
    for (std::uint32_t j = 0; j < ny; ++j)
      for (std::uint32_t i = 0; i < nx; ++i) refresh_tile((fx + i) % tiles_x_, (fy + j) % tiles_y_);
  }

  Extent table_;
  std::uint32_t tiles_x_, tiles_y_;
  std::vector<std::uint32_t> d2_;
  std::vector<Best> tile_best_;
};

}  // namespace

OffsetSequence OffsetSequence::farthest(Extent table, std::uint32_t count, std::uint64_t seed) {
  if (count == 0) throw std::invalid_argument("offset count must be positive");
  if (table.area() == 0) throw std::invalid_argument("offsets: table " + table.str() + " has no slots");
  if (table.area() > kFarthestMaxSlots)
    throw std::invalid_argument("farthest offsets: table " + table.str() + " has more than 2^28 slots (the exact " +
                                "distance field would need " + std::to_string(table.area() * 4 >> 20) +
                                " MiB); use random offsets or an offsets file");
  const auto n = static_cast<std::uint32_t>(std::min<std::uint64_t>(count, table.area()));
  SplitMix64 rng(seed ^ 0xBB67AE8584CAA73Bull);
  std::vector<glm::uvec2> picked;
  picked.reserve(n);
  picked.emplace_back(static_cast<std::uint32_t>(rng.below(table.x)), static_cast<std::uint32_t>(rng.below(table.y)));
  DistanceField field(table);
  field.add(picked.back());
  while (picked.size() < n) {
    picked.push_back(field.argmax());
    field.add(picked.back());
  }
  return OffsetSequence(table, OffsetGenerator::Farthest, std::move(picked), count);
}

}  // namespace habuffer
