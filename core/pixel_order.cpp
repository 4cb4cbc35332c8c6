#include "pixel_order.h"

namespace habuffer::detail {

std::vector<RowBand> balanced_row_bands(std::span<const Fragment> fragments, Extent screen, std::uint32_t parts) {
  parts = std::max(1u, std::min(parts, screen.y));
  if (parts == 1) return {RowBand{0, screen.y}};
  std::vector<std::uint64_t> per_row(screen.y, 0);
  for (const Fragment& f : fragments) ++per_row[f.y];
  std::vector<RowBand> bands;
  const std::uint64_t total = fragments.size();
  std::uint64_t seen = 0;
  std::uint32_t y0 = 0;
  for (std::uint32_t y = 0; y < screen.y; ++y) {
    seen += per_row[y];
    // Close band b once it holds its share: (b + 1) / parts of the fragments.
    const std::uint64_t share = total * (bands.size() + 1) / parts;
    if (bands.size() + 1 < parts && seen >= share && seen > 0) {
      bands.push_back({y0, y + 1});
      y0 = y + 1;
    }
  }
  bands.push_back({y0, screen.y});
  return bands;
}

}  // namespace habuffer::detail
