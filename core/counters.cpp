#include "habuffer/fragment.h"

#include "../shared/ha_constants.h"

namespace habuffer {

void Counters::count(std::uint32_t outcome) {
  ++fragments;
  switch (outcome) {
    case HA_STORED: break;
    case HA_DUPLICATE: ++duplicates; break;
    case HA_CULLED: ++culled; break;
    case HA_FAILED_AGE: ++failed_age; break;
    case HA_FAILED_ITER: ++failed_iter; break;
    case HA_INVALID: ++invalid; break;
    default: break;
  }
}

void Counters::add_tally(const std::uint64_t* tally) {
  for (std::uint32_t o = 0; o < HA_OUTCOME_COUNT; ++o) fragments += tally[o];
  duplicates += tally[HA_DUPLICATE];
  culled += tally[HA_CULLED];
  failed_age += tally[HA_FAILED_AGE];
  failed_iter += tally[HA_FAILED_ITER];
  invalid += tally[HA_INVALID];
}

Counters& Counters::operator+=(const Counters& o) {
  fragments += o.fragments;
  invalid += o.invalid;
  duplicates += o.duplicates;
  culled += o.culled;
  failed_age += o.failed_age;
  failed_iter += o.failed_iter;
  return *this;
}

}  // namespace habuffer
