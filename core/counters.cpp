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
    case HA_DROPPED_POOL: ++dropped_pool; break;
    case HA_DROPPED_LAYERS: ++dropped_layers; break;
    case HA_SATURATED: ++saturated_rejected; break;
    case HA_OCCUPANCY_REJECTED: ++occupancy_rejected; break;
    case HA_BLENDED: ++blended; break;
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
  dropped_pool += tally[HA_DROPPED_POOL];
  dropped_layers += tally[HA_DROPPED_LAYERS];
  saturated_rejected += tally[HA_SATURATED];
  occupancy_rejected += tally[HA_OCCUPANCY_REJECTED];
  blended += tally[HA_BLENDED];
}

Counters& Counters::operator+=(const Counters& o) {
  fragments += o.fragments;
  invalid += o.invalid;
  duplicates += o.duplicates;
  culled += o.culled;
  failed_age += o.failed_age;
  failed_iter += o.failed_iter;
  dropped_pool += o.dropped_pool;
  dropped_layers += o.dropped_layers;
  saturated_rejected += o.saturated_rejected;
  occupancy_rejected += o.occupancy_rejected;
  blended += o.blended;
  return *this;
}

}  // namespace habuffer
