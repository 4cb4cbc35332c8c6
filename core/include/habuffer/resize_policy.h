/// @file
/// Adaptive table sizing of SPEC 8: grow the area by `step` above `grow_at`
/// load, shrink it by `step` below `shrink_at`, never below the screen.
#pragma once

#include <cstdint>

#include "habuffer/extent.h"

namespace habuffer {

/// The thresholds and step of adaptive sizing (SPEC 8); load = stored / capacity.
struct ResizePolicy {
  double grow_at = 0.80;  ///< grow above this load
  double shrink_at = 0.30;  ///< shrink below this load
  double step = 0.25;  ///< fraction of the area (or capacity) to grow or shrink by

  /// Throws std::invalid_argument unless 0 <= shrink_at < grow_at <= 1 and 0 < step < 1.
  void validate() const;

  /// The table for the next frame, given this frame's stored-record count.
  [[nodiscard]] Extent next(Extent table, Extent screen, std::uint64_t stored) const;
  /// Area times (1 + step), aspect ratio kept, sides rounded up.
  [[nodiscard]] Extent grown(Extent table) const;

  /// The same rules for a capacity counted in records (the linked lists'
  /// pool), at least 1: the next frame's from the records `used` this frame,
  /// and lossless growth to at least `needed` and at least one step.
  [[nodiscard]] std::uint64_t next(std::uint64_t capacity, std::uint64_t used) const;
  /// An automatic pool's first size for `records` records: the records at
  /// grow_at use (so one pool holds them all), at least 1. The library,
  /// render and the CLI size every automatic pool so.
  [[nodiscard]] std::uint64_t automatic(std::uint64_t records) const;
  /// An automatic table's first size for `records` records on `screen`:
  /// the records at the middle of the band ((grow_at + shrink_at) / 2),
  /// the screen's aspect kept, sides rounded up, at least the screen.
  /// Throws std::invalid_argument beyond 2^32 - 1 slots.
  [[nodiscard]] Extent initial_table(Extent screen, std::uint64_t records) const;
  /// Lossless growth of a capacity: the largest of `needed`, capacity times (1 + step) rounded up, and capacity + 1.
  [[nodiscard]] std::uint64_t grown(std::uint64_t capacity, std::uint64_t needed) const;
  /// Area times (1 - step), aspect ratio kept, sides rounded up, at least the screen.
  [[nodiscard]] Extent shrunk(Extent table, Extent screen) const;
};

}  // namespace habuffer
