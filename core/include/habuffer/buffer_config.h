/// @file
/// Everything that fixes one HA-buffer besides its offsets.
#pragma once

#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/record_layout.h"
#include "shared/ha_constants.h"

namespace habuffer {

struct BufferConfig {
  Extent screen;
  Extent table;  ///< zero: the screen size
  Layout layout = Layout::L64;
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;
  std::uint32_t block = HABUFFER_DEFAULT_BLOCK;
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;
  float early_cull_tau = 0.0f;  ///< 0: off; else in (0, 1], L64 only
  /// With early cull: a culled fragment's depth code goes to a per-pixel
  /// saturation image (atomic max), and later fragments strictly behind it
  /// are rejected before insertion (saturated_rejected; guacamole, Fig. 6).
  bool saturation = false;

  [[nodiscard]] Extent table_or_screen() const { return table.area() == 0 ? screen : table; }
  [[nodiscard]] RecordLayout record_layout() const { return {layout, age_bits}; }
  /// Throws std::invalid_argument with a message naming the field and values
  /// (geometry rule of SPEC 1, age bits, block, cull threshold, size limits).
  void validate() const;
};

}  // namespace habuffer
