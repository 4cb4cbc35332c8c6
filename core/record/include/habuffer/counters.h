/// @file
/// The counters of SPEC invariant 1, for every technique: one field per
/// insert outcome, listed once in kCounterFields, from which the outcome
/// tally, the sums, the stats JSON, the result tables and the loss messages
/// are all read (no other list of the fields exists). A technique that adds
/// a drop reason adds its HABUFFER_* outcome (shared/ha_constants.h), its
/// field here and its row in kCounterFields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>

#include "habuffer/shared/ha_constants.h"

namespace habuffer {

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

  /// Fragments lost: every field of kind CounterKind::Failure (each
  /// technique's drop reasons and the occupancy rejections).
  [[nodiscard]] std::uint64_t failures() const;
  /// Records stored: the fragments less every other outcome (SPEC invariant 1).
  [[nodiscard]] std::uint64_t stored() const;
  /// Records the insert asked to keep: stored() plus failures(). What an
  /// overflowing frame needed, whatever its container could hold: adaptive
  /// sizing and lossless growth size by it (ResizePolicy).
  [[nodiscard]] std::uint64_t records_needed() const { return stored() + failures(); }
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

/// What an outcome counter means for the fragments it counts.
enum class CounterKind {
  Failure,  ///< lost for want of room or steps (failures(); lossless mode grows for these)
  Hidden,   ///< not stored because it is hidden (early cull, saturation): not a loss beyond tau
  Invalid,  ///< refused as invalid input (NaN depth or t outside [0, 1])
  Merged,   ///< kept once: a duplicate of a stored record
  Blended,  ///< blended into an image without being stored (the baselines)
};

/// One outcome counter of Counters (see the file comment).
struct CounterField {
  std::string_view name;              ///< the JSON key and table column
  std::uint64_t Counters::*member;    ///< the field
  std::uint32_t outcome;              ///< the HABUFFER_* insert outcome it counts
  CounterKind kind;                   ///< what it means
  std::string_view reason;            ///< how loss messages explain it ("" for none)
};

/// Every outcome counter but `fragments` (their sum) and the stored outcome,
/// in the order of the result tables' columns.
inline constexpr CounterField kCounterFields[] = {
    {"invalid", &Counters::invalid, HABUFFER_INVALID, CounterKind::Invalid,
     "depth NaN or outside [0, 1], or a coverage mask naming none of the samples"},
    {"duplicates", &Counters::duplicates, HABUFFER_DUPLICATE, CounterKind::Merged, ""},
    {"culled", &Counters::culled, HABUFFER_CULLED, CounterKind::Hidden, "early cull"},
    {"saturated_rejected", &Counters::saturated_rejected, HABUFFER_SATURATED, CounterKind::Hidden,
     "behind a culled fragment"},
    {"blended", &Counters::blended, HABUFFER_BLENDED, CounterKind::Blended, ""},
    {"failed_age", &Counters::failed_age, HABUFFER_FAILED_AGE, CounterKind::Failure, ""},
    {"failed_iter", &Counters::failed_iter, HABUFFER_FAILED_ITER, CounterKind::Failure, ""},
    {"dropped_pool", &Counters::dropped_pool, HABUFFER_DROPPED_POOL, CounterKind::Failure, "node pool full"},
    {"dropped_layers", &Counters::dropped_layers, HABUFFER_DROPPED_LAYERS, CounterKind::Failure,
     "pixel's layers full"},
    {"occupancy_rejected", &Counters::occupancy_rejected, HABUFFER_OCCUPANCY_REJECTED, CounterKind::Failure,
     "beyond the k nearest"},
};
static_assert(sizeof(Counters) == (std::size(kCounterFields) + 1) * sizeof(std::uint64_t),
              "every field of Counters but `fragments` needs its row in kCounterFields");
static_assert(std::size(kCounterFields) + 1 == HABUFFER_OUTCOME_COUNT,
              "every HABUFFER_* outcome but HABUFFER_STORED needs its counter and row in kCounterFields");

/// Fragments that are not stored and not a duplicate of a record that is:
/// failed (every CounterKind::Failure field), hidden (early cull) or invalid.
std::uint64_t lost_fragments(const Counters& c);

/// "19745 of 20000 fragments not stored: failed_age 19745, culled (early
/// cull) 3": the lost fragments and only the non-zero reasons, losses first,
/// then what was hidden, then what was refused (the loss messages of the
/// CLI and of lossless mode's DataError).
std::string loss_summary(const Counters& c);

}  // namespace habuffer
