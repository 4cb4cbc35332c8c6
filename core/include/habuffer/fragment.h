/// @file
/// Fragments (SPEC 1) and the counters of SPEC invariant 1, for every technique.
#pragma once

#include <cstdint>

namespace habuffer {

/// One rasterized fragment: pixel, normalized depth t (0 = nearest) and 32 bits
/// of data (R<<24 | G<<16 | B<<8 | A, straight alpha, for colour).
struct Fragment {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  float depth = 0.0f;
  std::uint32_t rgba = 0;
  friend bool operator==(const Fragment&, const Fragment&) = default;
};

/// Every insert call ends in exactly one outcome; `stored` follows from the
/// others, and equals the records the technique holds (the HA-buffer's
/// non-empty slots, the list nodes or array layers left after merging
/// duplicates). The drop reasons are each technique's own: failed_age and
/// failed_iter (HA-buffer), dropped_pool (linked lists), dropped_layers
/// (fixed arrays); all count as failures.
struct Counters {
  std::uint64_t fragments = 0;
  std::uint64_t invalid = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t culled = 0;
  std::uint64_t failed_age = 0;
  std::uint64_t failed_iter = 0;
  std::uint64_t dropped_pool = 0;
  std::uint64_t dropped_layers = 0;
  /// Rejected before insertion behind a pixel's saturation depth (early cull
  /// with saturation): hidden like culled ones, not a loss beyond tau.
  std::uint64_t saturated_rejected = 0;
  /// Rejected by the k-buffer's occupancy map: beyond the k nearest, lost as
  /// dropped_layers are.
  std::uint64_t occupancy_rejected = 0;
  /// Blended into the image without being stored (wboit, blend).
  std::uint64_t blended = 0;

  [[nodiscard]] std::uint64_t failures() const {
    return failed_age + failed_iter + dropped_pool + dropped_layers + occupancy_rejected;
  }
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

  Counters& operator+=(const Counters& o);
  friend bool operator==(const Counters&, const Counters&) = default;
};

}  // namespace habuffer
