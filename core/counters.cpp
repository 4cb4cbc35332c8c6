#include "habuffer/fragment.h"

#include "habuffer/shared/ha_constants.h"

namespace habuffer {

void Counters::count(std::uint32_t outcome) {
  ++fragments;
  switch (outcome) {
    case HABUFFER_STORED: break;
    case HABUFFER_DUPLICATE: ++duplicates; break;
    case HABUFFER_CULLED: ++culled; break;
    case HABUFFER_FAILED_AGE: ++failed_age; break;
    case HABUFFER_FAILED_ITER: ++failed_iter; break;
    case HABUFFER_INVALID: ++invalid; break;
    case HABUFFER_DROPPED_POOL: ++dropped_pool; break;
    case HABUFFER_DROPPED_LAYERS: ++dropped_layers; break;
    case HABUFFER_SATURATED: ++saturated_rejected; break;
    case HABUFFER_OCCUPANCY_REJECTED: ++occupancy_rejected; break;
    case HABUFFER_BLENDED: ++blended; break;
    default: break;
  }
}

void Counters::add_tally(const std::uint64_t* tally) {
  for (std::uint32_t o = 0; o < HABUFFER_OUTCOME_COUNT; ++o) fragments += tally[o];
  duplicates += tally[HABUFFER_DUPLICATE];
  culled += tally[HABUFFER_CULLED];
  failed_age += tally[HABUFFER_FAILED_AGE];
  failed_iter += tally[HABUFFER_FAILED_ITER];
  invalid += tally[HABUFFER_INVALID];
  dropped_pool += tally[HABUFFER_DROPPED_POOL];
  dropped_layers += tally[HABUFFER_DROPPED_LAYERS];
  saturated_rejected += tally[HABUFFER_SATURATED];
  occupancy_rejected += tally[HABUFFER_OCCUPANCY_REJECTED];
  blended += tally[HABUFFER_BLENDED];
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
