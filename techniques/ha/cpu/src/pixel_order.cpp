#include "pixel_order.h"

#include <bit>

namespace habuffer::detail {

std::uint64_t check_and_count_covered(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads,
                                      std::vector<std::vector<std::uint64_t>>& bitmaps) {
  threads = std::max<std::uint32_t>(1, threads);
  const std::size_t words = (screen.area() + 63) / 64;
  if (bitmaps.size() < threads) bitmaps.resize(threads);
  for (std::uint32_t t = 0; t < threads; ++t) bitmaps[t].assign(words, 0);
  for_slices_on_screen(fragments, screen, threads, [&](std::uint32_t t, const Fragment& f) {
    const std::size_t pixel = f.x + std::size_t{f.y} * screen.x;
    bitmaps[t][pixel / 64] |= std::uint64_t{1} << (pixel % 64);
  });
  std::uint64_t covered = 0;
  for (std::size_t w = 0; w < words; ++w) {
    std::uint64_t any = 0;
    for (std::uint32_t t = 0; t < threads; ++t) any |= bitmaps[t][w];
    covered += static_cast<std::uint64_t>(std::popcount(any));
  }
  return covered;
}

std::vector<RowBand> bands_from_rows(std::span<const std::uint64_t> per_row, std::uint32_t parts) {
  const auto rows = static_cast<std::uint32_t>(per_row.size());
  parts = std::max(1u, std::min(parts, rows));
  if (parts == 1) return {RowBand{0, rows}};
  std::uint64_t total = 0;
  for (const std::uint64_t n : per_row) total += n;
  std::vector<RowBand> bands;
  std::uint64_t seen = 0;
  std::uint32_t y0 = 0;
  for (std::uint32_t y = 0; y < rows; ++y) {
    seen += per_row[y];
    // Close band b once it holds its share: (b + 1) / parts of the records.
    const std::uint64_t share = total * (bands.size() + 1) / parts;
    if (bands.size() + 1 < parts && seen >= share && seen > 0) {
      bands.push_back({y0, y + 1});
      y0 = y + 1;
    }
  }
  bands.push_back({y0, rows});
  return bands;
}

}  // namespace habuffer::detail
