/// @file
/// Age vs load of the spatial hash on key streams (issue 22): the same keys
/// placed by four schemes, to measure what coherence and Robin Hood buy. A
/// serial simulator holds each record's key explicitly, so besides the
/// spatial hash's own scheme (coherent probing, Robin Hood; it builds the
/// very table of SpatialHash: tested) it runs the controls: independent
/// probing (a per-key pseudo-random slot per age) and first-come placement
/// (an occupied slot is never taken). Per variant and load, over trials
/// (each its own key set and offsets): mean and largest age, reads per hit
/// and per miss (a miss stops at the block's max age, and under Robin Hood
/// at the first slot holding a smaller record), failures past AMAX.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "habuffer/key_streams.h"

namespace habuffer::spatial {

enum class KeyProbing { Coherent, Independent };
enum class KeyPolicy { RobinHood, FirstCome };

/// The key experiment's variant lists by name, as parse_probings
/// (age_experiment.h): "coherent", "independent"; "robinhood", "fcfs".
std::vector<KeyProbing> parse_key_probings(const std::vector<std::string>& names);
std::vector<KeyPolicy> parse_key_policies(const std::vector<std::string>& names);  ///< see parse_key_probings

struct KeyExperimentConfig {
  KeySetOptions keys;                       ///< the key set (its seed + trial for each trial)
  std::vector<double> loads{0.5, 0.8, 0.9, 0.95, 0.99};  ///< in (0, 1]
  std::uint32_t trials = 5;
  std::vector<KeyProbing> probing{KeyProbing::Coherent, KeyProbing::Independent};
  std::vector<KeyPolicy> policy{KeyPolicy::RobinHood, KeyPolicy::FirstCome};
  std::uint32_t age_bits = 8;               ///< AMAX = 2^A - 1
  std::uint32_t block = 8;                  ///< the max-age block side
  std::uint32_t misses = 10000;             ///< absent keys looked up per trial
  std::uint64_t seed = 1;                   ///< offsets, insertion order and probe hash
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

struct KeyExperimentRow {
  std::string variant;            ///< "coherent/robinhood", ...
  double load = 0.0;              ///< target load
  double stored_load = 0.0;       ///< mean of stored keys / slots
  std::uint32_t trials = 0;
  double keys = 0.0;              ///< mean keys per trial
  double mean_age = 0.0, mean_age_ci95 = 0.0;  ///< mean over trials of the mean age (Student t half-width)
  double mean_max_age = 0.0;      ///< mean over trials of the largest age
  std::uint32_t max_age = 0;      ///< largest over trials
  double hit_reads = 0.0;         ///< slots read per lookup of a present key (its age)
  double miss_reads = 0.0, miss_reads_ci95 = 0.0;  ///< slots read per lookup of an absent key
  double failures = 0.0;          ///< mean keys per trial not placed (age past AMAX)
};

/// One row per variant and load, variants in the order probing x policy.
std::vector<KeyExperimentRow> run_key_experiment(const KeyExperimentConfig& config);

/// The simulator's table for `keys` (in order) with the spatial hash's own
/// scheme, as SpatialHash packs its slots (the test's cross-check).
std::vector<std::uint64_t> simulate_coherent_robin_hood(const std::vector<glm::uvec3>& keys, Domain domain,
                                                        Extent table, std::uint32_t age_bits,
                                                        const OffsetSequence& offsets);

}  // namespace habuffer::spatial
