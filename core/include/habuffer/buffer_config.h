/// @file
/// Everything that fixes one HA-buffer besides its offsets.
#pragma once

#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/record_layout.h"
#include "shared/ha_constants.h"

namespace habuffer {

/// One HA-buffer: screen, table, record layout, max-age block, iteration
/// limit and early cull.
struct BufferConfig {
  Extent screen;  ///< V, in pixels
  Extent table;  ///< 0x0: the screen size (one zero side is refused)
  Layout layout = Layout::L64;  ///< record layout (SPEC 2)
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< A (SPEC 2), 4..12
  std::uint32_t block = HABUFFER_DEFAULT_BLOCK;  ///< B, the max-age table's block side in pixels (SPEC 5)
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;  ///< LIMIT of SPEC 6: iterations of one insert call
  float early_cull_tau = 0.0f;  ///< 0: off; else in (0, 1], L64 only
  /// With early cull: a culled fragment's depth code goes to a per-pixel
  /// saturation image (atomic max), and later fragments strictly behind it
  /// are rejected before insertion (saturated_rejected; guacamole, Fig. 6).
  bool saturation = false;

  /// The table H: `table`, or the screen when `table` is 0x0.
  [[nodiscard]] Extent table_or_screen() const { return table == Extent{} ? screen : table; }
  /// The record layout of `layout` and `age_bits`; throws std::invalid_argument for age bits outside 4..12.
  [[nodiscard]] RecordLayout record_layout() const { return {layout, age_bits}; }
  /// Throws std::invalid_argument with a message naming the field and values
  /// (a screen or table with a zero side, geometry rule of SPEC 1, age bits,
  /// block, cull threshold, size limits).
  void validate() const;
  /// Memberwise equality.
  friend bool operator==(const BufferConfig&, const BufferConfig&) = default;
};

}  // namespace habuffer
