#include "habuffer/max_age_table.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace habuffer {

MaxAgeTable::MaxAgeTable(Extent screen, std::uint32_t block) : block_(block) {
  if (block == 0) throw std::invalid_argument("max-age block size must be at least 1");
  if (screen.area() == 0) throw std::invalid_argument("max-age table: screen " + screen.str() + " has no pixels");
  cells_ = {(screen.x + block - 1) / block, (screen.y + block - 1) / block};
  ages_.assign(cells_.area(), 0);
}

std::uint32_t MaxAgeTable::at(std::uint32_t cx, std::uint32_t cy) const {
  if (cx >= cells_.x || cy >= cells_.y)
    throw std::out_of_range("max-age cell (" + std::to_string(cx) + "," + std::to_string(cy) + ") lies outside cells " +
                            cells_.str());
  return ages_[cx + std::size_t{cy} * cells_.x];
}

std::uint32_t MaxAgeTable::max() const { return ages_.empty() ? 0 : *std::max_element(ages_.begin(), ages_.end()); }

void MaxAgeTable::clear() { std::fill(ages_.begin(), ages_.end(), 0u); }

}  // namespace habuffer
