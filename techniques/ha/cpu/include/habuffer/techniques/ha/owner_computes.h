/// @file
/// Parallel insertion without atomics: the table's rows are dealt out to
/// owners in interleaved bands, and only a slot's owner ever touches it.
///
/// A thread runs the shared insert steps (ha_insert_step) while the carried
/// record probes slots of its own bands, and hands the record over (a message
/// with the whole insert state, HabufferCarry) as soon as it probes another owner's
/// slot. Messages are exchanged in rounds until none is left. Since each slot
/// keeps the largest record proposed to it, the final table does not depend on
/// the order of proposals (SPEC 9), so this gives the very table a serial
/// build gives, with plain loads and stores, and threads share a cache line
/// only at band edges. Each owner keeps a private max-age table; they are
/// merged by maximum at the end.
#pragma once

#include <cstdint>
#include <span>

#include "habuffer/fragment.h"
#include "habuffer/hash_kernel.h"
#include "habuffer/max_age_table.h"

namespace habuffer {

/// How insert_owner_computes deals out the table.
struct OwnerComputesOptions {
  std::uint32_t owners = 2;      ///< logical owners (one task each per round)
  std::uint32_t band_rows = 16;  ///< table rows per band; bands go round-robin to owners
};

/// Inserts `fragments` into `table` and `max_age` by owner-computes (see above),
/// with `params` and `offsets` as HashKernel takes them; returns the counters.
/// Throws std::invalid_argument when options.owners or options.band_rows is 0.
template <class Word>
Counters insert_owner_computes(const KernelParams& params, const glm::uvec2* offsets, Word* table,
                               MaxAgeTable& max_age, std::span<const Fragment> fragments,
                               const OwnerComputesOptions& options);

extern template Counters insert_owner_computes<std::uint64_t>(const KernelParams&, const glm::uvec2*, std::uint64_t*,
                                                              MaxAgeTable&, std::span<const Fragment>,
                                                              const OwnerComputesOptions&);
extern template Counters insert_owner_computes<std::uint32_t>(const KernelParams&, const glm::uvec2*, std::uint32_t*,
                                                              MaxAgeTable&, std::span<const Fragment>,
                                                              const OwnerComputesOptions&);

}  // namespace habuffer
