/// @file
/// The max-age table M of SPEC 5: one cell per B x B block of pixels, holding
/// the largest age at which a record of one of its pixels was placed.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/extent.h"

namespace habuffer {

class MaxAgeTable {
 public:
  MaxAgeTable() = default;
  /// Throws std::invalid_argument when block is 0.
  MaxAgeTable(Extent screen, std::uint32_t block);

  [[nodiscard]] Extent cells() const { return cells_; }
  [[nodiscard]] std::uint32_t block() const { return block_; }
  [[nodiscard]] std::uint32_t cell_index(std::uint32_t px, std::uint32_t py) const {
    return px / block_ + (py / block_) * cells_.x;
  }
  [[nodiscard]] std::uint32_t at(std::uint32_t cx, std::uint32_t cy) const { return ages_[cx + cy * cells_.x]; }
  [[nodiscard]] std::uint32_t max() const;
  [[nodiscard]] std::uint32_t* data() { return ages_.data(); }
  [[nodiscard]] const std::vector<std::uint32_t>& ages() const { return ages_; }
  [[nodiscard]] std::uint64_t bytes() const { return ages_.size() * sizeof(std::uint32_t); }
  void clear();

 private:
  Extent cells_;
  std::uint32_t block_ = 0;
  std::vector<std::uint32_t> ages_;
};

}  // namespace habuffer
