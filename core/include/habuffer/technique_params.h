// What the list and array kernels read besides their buffers (their GLSL
// "uniforms"), on the CPU path; the GPU path's are in the shared parameter
// block (core/shared/ha_params.h).
#pragma once

#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/technique.h"
#include "../../shared/ha_constants.h"

namespace habuffer {

struct TechniqueParams {
  std::uint32_t age_bits = HA_DEFAULT_AGE_BITS;  // fixes the depth code's bits (SPEC 2)
  std::uint32_t payload_bits = 32;               // 32 for L64, 0 for L32 (data stored as 0)
  Extent screen;
  std::uint32_t pool_capacity = 0;  // linked lists: nodes
  std::uint32_t layers = HA_DEFAULT_LAYERS;  // fixed arrays: K
};

inline TechniqueParams make_technique_params(const TechniqueConfig& c) {
  TechniqueParams p;
  p.age_bits = c.buffer.age_bits;
  p.payload_bits = c.buffer.layout == Layout::L64 ? 32 : 0;
  p.screen = c.buffer.screen;
  p.pool_capacity = static_cast<std::uint32_t>(c.pool_capacity);
  p.layers = c.layers;
  return p;
}

}  // namespace habuffer
