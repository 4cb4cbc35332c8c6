/// @file
/// Adaptive sizing of SPEC 8, for the HA-buffer's table and the node pools,
/// on both paths (one set of functions: the CPU's TechniqueFrames and
/// render, the GL containers and Python all decide here).
///
/// The paper's thresholds decide *when* a size changes: a frame whose load
/// (records over capacity) leaves the band [shrink_at, grow_at]. What decides
/// *how much* is the rule:
///  - ResizeRule::Count (the default, ours): the next size holds the records
///    the frame asked to keep (stored plus failed: Counters::records_needed,
///    so an overflowing frame is judged by what it received, not by what it
///    could store) at the middle of the band, in one decision. A jump of any
///    size takes one resize between frames, and one lossless regather within
///    a frame; landing mid-band is the hysteresis (a load oscillating a few
///    per cent around either threshold resizes at most once).
///  - ResizeRule::Step (the paper's): one `step` of the area per decision,
///    for studies that want it.
#pragma once

#include <cstdint>
#include <string_view>

#include "habuffer/extent.h"

namespace habuffer {

/// How far one sizing decision moves (see the file comment).
enum class ResizeRule : std::uint8_t {
  Count,  ///< to the counted records at the middle of the band, in one decision
  Step,   ///< one `step` of the area (or capacity) per decision (the paper's)
};

/// "count" or "step".
std::string_view to_string(ResizeRule rule);
/// The rule spelled `text` ("count", "step"); throws std::invalid_argument naming the spellings.
ResizeRule parse_resize_rule(std::string_view text);

/// The thresholds, step and rule of adaptive sizing (SPEC 8); load = records / capacity.
struct ResizePolicy {
  double grow_at = 0.80;  ///< grow above this load
  double shrink_at = 0.30;  ///< shrink below this load
  double step = 0.25;  ///< ResizeRule::Step: fraction of the area (or capacity) to grow or shrink by
  ResizeRule rule = ResizeRule::Count;  ///< how far one decision moves

  /// Throws std::invalid_argument unless 0 <= shrink_at < grow_at <= 1 and 0 < step < 1.
  void validate() const;
  /// The load a counted size aims at: the middle of the band, (grow_at + shrink_at) / 2.
  [[nodiscard]] double target_load() const { return (grow_at + shrink_at) / 2.0; }

  /// The table for the next frame, given the records this frame asked to
  /// keep (stored + failed; for a frame that failed nothing, its stored
  /// records): the same table inside the band, else (Count) the table for
  /// those records at target_load() or (Step) one step, never below the
  /// screen. A counted table beyond 2^32 - 1 slots is capped there (the
  /// caller's limits decide what it can allocate).
  [[nodiscard]] Extent next(Extent table, Extent screen, std::uint64_t records) const;
  /// Lossless growth within a frame after an attempt into `table` that
  /// asked for `records` records (stored + failed) and failed some: Count,
  /// the table for them at target_load() (one regather holds a jump of any
  /// size), Step, one step; always strictly larger than `table` (a failure
  /// at a load inside the band still grows). Capped like next().
  [[nodiscard]] Extent grown(Extent table, Extent screen, std::uint64_t records) const;
  /// Area times (1 + step), aspect ratio kept, sides rounded up (the Step rule's growth).
  [[nodiscard]] Extent grown(Extent table) const;

  /// The same rules for a capacity counted in records (a node pool), at
  /// least 1: the next frame's from the records `used` this frame (the nodes
  /// it asked for, dropped ones included).
  [[nodiscard]] std::uint64_t next(std::uint64_t capacity, std::uint64_t used) const;
  /// An automatic pool's first size for `records` records: the records at
  /// grow_at use (so one pool holds them all), at least 1. The library,
  /// render and the CLI size every automatic pool so.
  [[nodiscard]] std::uint64_t automatic(std::uint64_t records) const;
  /// An automatic table's first size for `records` records on `screen`:
  /// the records at target_load(), the screen's aspect kept, sides rounded
  /// up, at least the screen. Throws std::invalid_argument beyond 2^32 - 1 slots.
  [[nodiscard]] Extent initial_table(Extent screen, std::uint64_t records) const;
  /// Lossless growth of a capacity after an attempt that asked for `needed`:
  /// Count, the larger of `needed` at target_load() (rounded up) and
  /// capacity + 1; Step, the largest of `needed`, capacity times (1 + step)
  /// rounded up, and capacity + 1.
  [[nodiscard]] std::uint64_t grown(std::uint64_t capacity, std::uint64_t needed) const;
  /// Area times (1 - step), aspect ratio kept, sides rounded up, at least the screen.
  [[nodiscard]] Extent shrunk(Extent table, Extent screen) const;
  /// The capacity holding `records` at target_load(), rounded up, at least 1.
  [[nodiscard]] std::uint64_t counted_capacity(std::uint64_t records) const;

  /// Memberwise equality.
  friend bool operator==(const ResizePolicy&, const ResizePolicy&) = default;
};

}  // namespace habuffer
