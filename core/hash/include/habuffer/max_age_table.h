/// @file
/// The max-age table M of SPEC 5: one cell per B x B block of pixels, holding
/// the largest age at which a record of one of its pixels was placed.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/extent.h"

namespace habuffer {

/// The max-age table M (SPEC 5).
class MaxAgeTable {
 public:
  /// An empty table: no cells.
  MaxAgeTable() = default;
  /// Throws std::invalid_argument when block is 0 or the screen has no pixels.
  MaxAgeTable(Extent screen, std::uint32_t block);

  /// Cells per row and column: the screen divided by B, rounded up.
  [[nodiscard]] Extent cells() const { return cells_; }
  /// B, the block side in pixels.
  [[nodiscard]] std::uint32_t block() const { return block_; }
  /// Row-major index of pixel (px, py)'s cell.
  [[nodiscard]] std::uint32_t cell_index(std::uint32_t px, std::uint32_t py) const {
    return px / block_ + (py / block_) * cells_.x;
  }
  /// Cell (cx, cy)'s max age; throws std::out_of_range for a cell outside cells().
  [[nodiscard]] std::uint32_t at(std::uint32_t cx, std::uint32_t cy) const;
  /// The largest max age of any cell (0 for an empty table).
  [[nodiscard]] std::uint32_t max() const;
  /// The cells, row-major, for a kernel to update.
  [[nodiscard]] std::uint32_t* data() { return ages_.data(); }
  /// The cells, row-major.
  [[nodiscard]] const std::vector<std::uint32_t>& ages() const { return ages_; }
  /// Bytes of the cells: 4 per cell.
  [[nodiscard]] std::uint64_t bytes() const { return ages_.size() * sizeof(std::uint32_t); }
  /// Zeroes every cell.
  void clear();

 private:
  Extent cells_;
  std::uint32_t block_ = 0;
  std::vector<std::uint32_t> ages_;
};

}  // namespace habuffer
