#include "habuffer/resize_policy.h"

#include "habuffer/option_rules.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace habuffer {
namespace {

Extent scaled(Extent table, double area_factor) {
  const double s = std::sqrt(area_factor);
  auto side = [&](std::uint32_t v) {
    const double r = std::ceil(static_cast<double>(v) * s);
    if (r > static_cast<double>(1u << 31)) throw std::length_error("table side would exceed 2^31 slots");
    return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(r));
  };
  return {side(table.x), side(table.y)};
}

}  // namespace

void ResizePolicy::validate() const {
  if (!(shrink_at >= 0.0 && shrink_at < grow_at && grow_at <= 1.0))
    throw std::invalid_argument("resize thresholds need 0 <= shrink_at (" + std::to_string(shrink_at) +
                                ") < grow_at (" + std::to_string(grow_at) + ") <= 1");
  if (!(step > 0.0 && step < 1.0))
    throw std::invalid_argument("resize step " + std::to_string(step) + " outside (0, 1)");
}

Extent ResizePolicy::grown(Extent table) const {
  Extent g = scaled(table, 1.0 + step);
  // Rounding up keeps growth strict even for a 1x1 table.
  if (g.area() <= table.area()) g.x = table.x + 1;
  return g;
}

std::uint64_t ResizePolicy::next(std::uint64_t capacity, std::uint64_t used) const {
  const double c = static_cast<double>(capacity), use = static_cast<double>(used) / c;
  if (use > grow_at) return static_cast<std::uint64_t>(std::ceil(c * (1.0 + step)));
  if (use < shrink_at) return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(c * (1.0 - step))));
  return capacity;
}

std::uint64_t ResizePolicy::automatic(std::uint64_t records) const {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(records) / grow_at)));
}

Extent ResizePolicy::initial_table(Extent screen, std::uint64_t records) const {
  return table_for_load(screen, records, (grow_at + shrink_at) / 2.0);
}

std::uint64_t ResizePolicy::grown(std::uint64_t capacity, std::uint64_t needed) const {
  const auto stepped = static_cast<std::uint64_t>(std::ceil(static_cast<double>(capacity) * (1.0 + step)));
  return std::max({needed, stepped, capacity + 1});
}

Extent ResizePolicy::shrunk(Extent table, Extent screen) const {
  const Extent s = scaled(table, 1.0 - step);
  return {std::max(s.x, screen.x), std::max(s.y, screen.y)};
}

Extent ResizePolicy::next(Extent table, Extent screen, std::uint64_t stored) const {
  const double load = static_cast<double>(stored) / static_cast<double>(table.area());
  if (load > grow_at) return grown(table);
  if (load < shrink_at) return shrunk(table, screen);
  return table;
}

}  // namespace habuffer
