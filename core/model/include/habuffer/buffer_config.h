/// @file
/// The fragment buffer's configuration every technique shares (screen,
/// record layout, age bits: they fix the depth code, so the lists of every
/// technique compare bit for bit), with the coherent hash's own fields
/// (table, max-age block) and those of the techniques that cull early (the
/// iteration limit, early cull, saturation: the HA-buffer, sorted lists).
#pragma once

#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/record_layout.h"
#include "habuffer/shared/ha_constants.h"

namespace habuffer {

/// A fragment buffer's configuration (see the file comment): what every
/// technique reads (screen, layout, age bits), what the HA-buffer reads
/// besides (table, block) and what the techniques with early cull read
/// (iteration limit, early cull, saturation). An HaBuffer is made from it
/// alone; the other techniques take it inside a TechniqueConfig, whose
/// relevant() sets the fields a technique does not read to their defaults.
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
  /// S, the samples of a multisampled screen: 1 (not multisampled), 2, 4 or
  /// 8. Above 1, every record carries the S-bit coverage mask of its
  /// fragment in the low bits of its code field, which leaves the depth
  /// 32 - A - S bits (docs/spec-notes.md, "Multisampled records").
  std::uint32_t samples = 1;

  /// The table H: `table`, or the screen when `table` is 0x0.
  [[nodiscard]] Extent table_or_screen() const { return table == Extent{} ? screen : table; }
  /// The record layout of `layout`, `age_bits` and `samples`; throws
  /// std::invalid_argument for age bits outside 4..12 or samples not 1, 2, 4 or 8.
  [[nodiscard]] RecordLayout record_layout() const { return {layout, age_bits, samples}; }
  /// Throws std::invalid_argument with a message naming the field and values
  /// (a screen or table with a zero side, geometry rule of SPEC 1, age bits,
  /// block, cull threshold, size limits).
  void validate() const;
  /// Memberwise equality.
  friend bool operator==(const BufferConfig&, const BufferConfig&) = default;
};

}  // namespace habuffer
