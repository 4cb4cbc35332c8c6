/// @file
/// The numbers that describe one build: counters (SPEC invariant 1), load,
/// ages and memory. The CLI writes them as stats JSON.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"

namespace habuffer {

/// What summarize() measures on one built container.
struct BuildReport {
  Counters counters;  ///< the build's counters, as given to summarize()
  std::uint64_t stored = 0;        ///< records held, measured on the buffer (the HA-buffer's non-empty slots)
  std::uint64_t capacity = 0;      ///< records it could hold (slots, nodes, layers of every pixel)
  double load_factor = 0.0;        ///< stored / capacity
  /// The HA-buffer's ages (zero and empty for other techniques).
  std::uint32_t max_age = 0;       ///< largest age of a stored record
  double mean_age = 0.0;           ///< over stored records
  std::vector<std::uint64_t> age_histogram;  ///< [a] = stored records of age a, a = 0..max_age
  std::uint32_t max_age_table_max = 0;       ///< largest cell of M
  Extent table;                    ///< the hash table's size (0x0 for techniques without one)
  std::uint64_t memory_bytes = 0;  ///< bytes the container allocated (FragmentBuffer::memory_bytes)
  std::uint64_t memory_model_bytes = 0;  ///< memory_model.h, for the buffer as it is
};

/// The report of `buffer` after a build that returned `counters`: stored records,
/// capacity, load and memory measured on the buffer, and the HA-buffer's ages.
BuildReport summarize(const FragmentBuffer& buffer, const Counters& counters);

}  // namespace habuffer
