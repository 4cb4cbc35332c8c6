/// @file
/// Fragments (SPEC 1) and the counters of SPEC invariant 1, for every technique.
#pragma once

#include <cstdint>

namespace habuffer {

/// One rasterized fragment: pixel, normalized depth t (0 = nearest) and 32 bits
/// of data (R<<24 | G<<16 | B<<8 | A, straight alpha, for colour).
struct Fragment {
  std::uint32_t x = 0;  ///< pixel column
  std::uint32_t y = 0;  ///< pixel row
  float depth = 0.0f;  ///< normalized depth t in [0, 1]; NaN or outside: invalid
  std::uint32_t rgba = 0;  ///< the 32-bit data word
  /// Memberwise equality.
  friend bool operator==(const Fragment&, const Fragment&) = default;
};

/// Every insert call ends in exactly one outcome; `stored` follows from the
/// others, and equals the records the technique holds (the HA-buffer's
/// non-empty slots, the list nodes or array layers left after merging
/// duplicates). The drop reasons are each technique's own: failed_age and
/// failed_iter (HA-buffer), dropped_pool (linked lists), dropped_layers
/// (fixed arrays); all count as failures.
struct Counters {
  std::uint64_t fragments = 0;  ///< every fragment inserted, whatever its outcome
  std::uint64_t invalid = 0;  ///< NaN depth or t outside [0, 1] (SPEC 2): not stored
  std::uint64_t duplicates = 0;  ///< equal to a record its pixel already holds: kept once
  std::uint64_t culled = 0;  ///< early cull: behind accumulated opacity above tau
  std::uint64_t failed_age = 0;  ///< HA-buffer: the carried record passed AMAX
  std::uint64_t failed_iter = 0;  ///< an insert call ran past the iteration limit (HA-buffer, sorted lists)
  std::uint64_t dropped_pool = 0;  ///< linked lists: the node pool was full
  std::uint64_t dropped_layers = 0;  ///< arrays: the pixel's K layers taken; k-buffer: behind the K-th
  /// Rejected before insertion behind a pixel's saturation depth (early cull
  /// with saturation): hidden like culled ones, not a loss beyond tau.
  std::uint64_t saturated_rejected = 0;
  /// Rejected by the k-buffer's occupancy map: beyond the k nearest, lost as
  /// dropped_layers are.
  std::uint64_t occupancy_rejected = 0;
  /// Blended into the image without being stored (wboit, blend).
  std::uint64_t blended = 0;

  /// Fragments lost: every technique's drop reasons and the occupancy rejections.
  [[nodiscard]] std::uint64_t failures() const {
    return failed_age + failed_iter + dropped_pool + dropped_layers + occupancy_rejected;
  }
  /// Records stored: the fragments less every other outcome (SPEC invariant 1).
  [[nodiscard]] std::uint64_t stored() const {
    return fragments - invalid - duplicates - culled - saturated_rejected - blended - failures();
  }
  /// Records counted stored at insertion and found equal to another record of
  /// their pixel when the lists were sorted: moved to duplicates.
  void merge_duplicates(std::uint64_t merged) { duplicates += merged; }
  /// Counts one insert outcome (an HA_* constant of ha_constants.h).
  void count(std::uint32_t outcome);
  /// Adds per-outcome totals, indexed by HA_* outcome (HABUFFER_OUTCOME_COUNT entries).
  void add_tally(const std::uint64_t* tally);

  /// Adds every counter of `o`.
  Counters& operator+=(const Counters& o);
  /// Memberwise equality.
  friend bool operator==(const Counters&, const Counters&) = default;
};

}  // namespace habuffer
