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

// The table holding `records` at `load` on `screen` (the screen's aspect,
// at least the screen), capped at 2^32 - 1 slots (same aspect) instead of
// refused: a sizing decision names what it wants, the container's limits
// what it gets.
Extent counted_table(Extent screen, std::uint64_t records, double load) {
  try {
    return table_for_load(screen, records, load);
  } catch (const std::invalid_argument&) {
    // beyond 2^32 - 1 slots: the largest table of the screen's aspect below it
  }
  const double s = std::sqrt(static_cast<double>(UINT32_MAX) * 0.999 / static_cast<double>(screen.area()));
  return {std::max<std::uint32_t>(screen.x, static_cast<std::uint32_t>(std::floor(screen.x * s))),
          std::max<std::uint32_t>(screen.y, static_cast<std::uint32_t>(std::floor(screen.y * s)))};
}

}  // namespace

std::string_view to_string(ResizeRule rule) { return rule == ResizeRule::Step ? "step" : "count"; }

ResizeRule parse_resize_rule(std::string_view text) {
  if (text == "count") return ResizeRule::Count;
  if (text == "step") return ResizeRule::Step;
  throw std::invalid_argument("resize rule '" + std::string(text) + "': expected count or step");
}

void ResizePolicy::validate() const {
  if (!(shrink_at >= 0.0 && shrink_at < grow_at && grow_at <= 1.0))
    throw std::invalid_argument("resize thresholds need 0 <= shrink_at (" + std::to_string(shrink_at) +
                                ") < grow_at (" + std::to_string(grow_at) + ") <= 1");
  if (!(step > 0.0 && step < 1.0))
    throw std::invalid_argument("resize step " + std::to_string(step) + " outside (0, 1)");
  if (rule != ResizeRule::Count && rule != ResizeRule::Step)
    throw std::invalid_argument("resize rule " + std::to_string(static_cast<int>(rule)) + " is neither count nor step");
}

Extent ResizePolicy::grown(Extent table) const {
  Extent g = scaled(table, 1.0 + step);
  // Rounding up keeps growth strict even for a 1x1 table.
  if (g.area() <= table.area()) g.x = table.x + 1;
  return g;
}

Extent ResizePolicy::grown(Extent table, Extent screen, std::uint64_t records) const {
  if (rule == ResizeRule::Step) return grown(table);
  const Extent counted = counted_table(screen, records, target_load());
  // A failure inside the band (an unlucky pixel) still grows: one step.
  return counted.area() > table.area() ? counted : grown(table);
}

std::uint64_t ResizePolicy::counted_capacity(std::uint64_t records) const {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(records) / target_load())));
}

std::uint64_t ResizePolicy::next(std::uint64_t capacity, std::uint64_t used) const {
  const double c = static_cast<double>(capacity), use = static_cast<double>(used) / c;
  if (use <= grow_at && use >= shrink_at) return capacity;
  if (rule == ResizeRule::Count) return counted_capacity(used);
  if (use > grow_at) return static_cast<std::uint64_t>(std::ceil(c * (1.0 + step)));
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(c * (1.0 - step))));
}

std::uint64_t ResizePolicy::automatic(std::uint64_t records) const {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(records) / grow_at)));
}

Extent ResizePolicy::initial_table(Extent screen, std::uint64_t records) const {
  return table_for_load(screen, records, target_load());
}

std::uint64_t ResizePolicy::grown(std::uint64_t capacity, std::uint64_t needed) const {
  if (rule == ResizeRule::Count) return std::max(counted_capacity(needed), capacity + 1);
  const auto stepped = static_cast<std::uint64_t>(std::ceil(static_cast<double>(capacity) * (1.0 + step)));
  return std::max({needed, stepped, capacity + 1});
}

Extent ResizePolicy::shrunk(Extent table, Extent screen) const {
  const Extent s = scaled(table, 1.0 - step);
  return {std::max(s.x, screen.x), std::max(s.y, screen.y)};
}

Extent ResizePolicy::next(Extent table, Extent screen, std::uint64_t records) const {
  const double load = static_cast<double>(records) / static_cast<double>(table.area());
  if (load <= grow_at && load >= shrink_at) return table;
  if (rule == ResizeRule::Step) return load > grow_at ? grown(table) : shrunk(table, screen);
  const Extent counted = counted_table(screen, records, target_load());
  // Below the band at the screen already: nothing smaller exists.
  if (load < shrink_at && counted.area() >= table.area()) return table;
  return counted;
}

}  // namespace habuffer
