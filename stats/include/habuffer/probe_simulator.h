/// @file
/// A serial, instrumented model of HA-buffer insertion for experiments on age
/// vs load: it stores each record's pixel explicitly, so besides the SPEC's
/// coherent probing with Robin Hood eviction it can run the controls the SPEC
/// cannot: independent (per-pixel pseudo-random) probe sequences, and
/// first-come-first-served placement without eviction. Coherent + Robin Hood
/// builds the very table of an L32 HaBuffer (checked by the tests).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "habuffer/fragment.h"
#include "habuffer/offset_sequence.h"

namespace habuffer {

/// The probe sequence of a record of pixel p and age a.
enum class Probing {
  Coherent,    ///< the SPEC's: p plus the age's offset, shared by every pixel (SPEC 1)
  Independent  ///< a per-pixel pseudo-random slot (a hash of p, a and the seed): the control
};
/// What happens when a probed slot is taken.
enum class Policy {
  RobinHood,  ///< the larger (age, code) keeps the slot, the other moves on to its next age (SPEC 3)
  Fcfs        ///< first come, first served: only an empty slot is taken, nothing is evicted
};

/// One simulated table.
struct SimulatorConfig {
  Extent screen;                        ///< pixels
  Extent table;                         ///< slots, at least the screen on each side
  std::uint32_t age_bits = 8;           ///< AMAX = 2^age_bits - 1; the L32 word keeps 32 - age_bits code bits
  std::uint32_t block = 8;              ///< side of a max-age cell, pixels (SPEC 5)
  Probing probing = Probing::Coherent;  ///< probe sequence
  Policy policy = Policy::RobinHood;    ///< placement
  std::uint64_t seed = 1;           ///< offsets (coherent) or probe hash (independent)
  OffsetGenerator offsets = OffsetGenerator::Random;  ///< coherent probing's offsets
  std::uint32_t iter_limit = 65536;  ///< probes one insert call may take before it fails (failed_iter)
};

/// What a simulation measured (ProbeSimulator::totals).
struct SimulatorTotals {
  Counters counters;                         ///< insert outcomes, as the HA-buffer counts them
  std::vector<std::uint64_t> age_histogram;  ///< [a] = stored records of age a
  std::uint64_t probes = 0;                  ///< slots probed by all insert calls
  std::uint32_t max_probes = 0;              ///< most slots probed by one insert call
  std::uint64_t traversal_probes = 0;        ///< slots read by traversing every screen pixel
  std::uint64_t wasted_traversal_probes = 0;  ///< of those, read after the pixel's last record
  std::uint64_t pixels = 0;                  ///< screen pixels traversed
};

/// One table under simulation (see the file comment).
class ProbeSimulator {
 public:
  /// An empty table; throws std::invalid_argument when the table is smaller than the screen.
  explicit ProbeSimulator(const SimulatorConfig& config);

  /// Inserts `fragments` serially, in order; throws std::out_of_range for a fragment outside the screen.
  void insert(std::span<const Fragment> fragments);
  /// Traverses every pixel (SPEC 7; FCFS cannot stop early and reads up to the
  /// block's max age) and returns all totals.
  [[nodiscard]] SimulatorTotals totals() const;
  /// The stored record of slot s as an L32 word (age << (32 - age_bits) | code), 0 if empty; throws
  /// std::out_of_range for a slot beyond the table.
  [[nodiscard]] std::uint32_t l32_word(std::uint64_t s) const;

 private:
  struct Entry {
    std::uint32_t age = 0;  // 0: empty
    std::uint32_t code = 0;
    std::uint32_t pixel = 0;
    friend auto operator<=>(const Entry&, const Entry&) = default;
  };
  [[nodiscard]] std::uint64_t probe(std::uint32_t pixel, std::uint32_t age) const;
  [[nodiscard]] std::uint32_t cell(std::uint32_t pixel) const;
  std::uint32_t insert_one(std::uint32_t pixel, std::uint32_t code);

  SimulatorConfig config_;
  std::uint32_t amax_;
  std::uint32_t depth_bits_;
  OffsetSequence offsets_;
  std::vector<Entry> table_;
  std::vector<std::uint32_t> max_age_;
  std::uint32_t cells_x_;
  SimulatorTotals totals_;
};

}  // namespace habuffer
