/// @file
/// The GPU paths' outcome tallies read back: each counter summed over its
/// stripes (entry_common.glsl's ha_counter_add writes HABUFFER_COUNTER_STRIPES
/// copies, one cache line each). One reader for OpenGL and Vulkan.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "habuffer/shared/ha_constants.h"

namespace habuffer {

/// Each of the HABUFFER_GPU_COUNTER_COUNT counters summed over the stripes of
/// `words` (at least HABUFFER_COUNTER_WORDS of them).
inline std::array<std::uint64_t, HABUFFER_GPU_COUNTER_COUNT> stripe_tally(std::span<const std::uint32_t> words) {
  static_assert(HABUFFER_GPU_COUNTER_COUNT <= HABUFFER_COUNTER_STRIDE, "a stripe's counters fit its cache line");
  std::array<std::uint64_t, HABUFFER_GPU_COUNTER_COUNT> tally{};
  for (std::uint32_t stripe = 0; stripe < HABUFFER_COUNTER_STRIPES; ++stripe)
    for (std::uint32_t k = 0; k < HABUFFER_GPU_COUNTER_COUNT; ++k) tally[k] += words[stripe * HABUFFER_COUNTER_STRIDE + k];
  return tally;
}

}  // namespace habuffer
