#include "habuffer/option_rules.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "habuffer/number_text.h"

namespace habuffer {

float parse_cull_threshold(std::string_view text) {
  const float tau = parse_float32(text);
  if (!(tau >= std::numeric_limits<float>::min() && tau <= 1.0f))
    throw std::invalid_argument("threshold must be in (0, 1], at least " +
                                shortest_text(std::numeric_limits<float>::min()) +
                                " (the smallest normal float32), not " + std::string(text));
  return tau;
}

double parse_load_factor(std::string_view text) {
  const double load = parse_float64(text);
  if (!(load > 0.0 && load <= 1.0)) throw std::invalid_argument("load must be in (0, 1], not " + std::string(text));
  return load;
}

Extent table_of_sides(double x, double y, double load, std::uint64_t fragments) {
  const double side = static_cast<double>(std::uint32_t{1} << 31);
  if (!(x <= side && y <= side && x * y <= static_cast<double>(UINT32_MAX)))
    throw std::invalid_argument("load " + shortest_text(load) + " of " + std::to_string(fragments) +
                                " fragments needs a table of " + shortest_text(x * y) +
                                " slots, more than 2^32 - 1: raise the load");
  return {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)};
}

Extent table_for_load(Extent screen, std::uint64_t fragments, double load) {
  if (!(load > 0.0)) throw std::invalid_argument("load must be positive");
  const double scale = std::sqrt(static_cast<double>(fragments) / load / static_cast<double>(screen.area()));
  return table_of_sides(std::max<double>(screen.x, std::ceil(screen.x * scale)),
                        std::max<double>(screen.y, std::ceil(screen.y * scale)), load, fragments);
}

}  // namespace habuffer
