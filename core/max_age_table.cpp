#include "habuffer/max_age_table.h"

#include <algorithm>
#include <stdexcept>

namespace habuffer {

MaxAgeTable::MaxAgeTable(Extent screen, std::uint32_t block) : block_(block) {
  if (block == 0) throw std::invalid_argument("max-age block size must be at least 1");
  cells_ = {(screen.x + block - 1) / block, (screen.y + block - 1) / block};
  ages_.assign(cells_.area(), 0);
}

std::uint32_t MaxAgeTable::max() const { return ages_.empty() ? 0 : *std::max_element(ages_.begin(), ages_.end()); }

void MaxAgeTable::clear() { std::fill(ages_.begin(), ages_.end(), 0u); }

}  // namespace habuffer
