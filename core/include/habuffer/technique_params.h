/// @file
/// What the list and array kernels read besides their buffers (their GLSL
/// "uniforms"), on the CPU path; the GPU path's are in the shared parameter
/// block (core/include/habuffer/shared/ha_params.h).
#pragma once

#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/technique.h"
#include "shared/ha_constants.h"

namespace habuffer {

/// The list, array, k-buffer and blended kernels' parameters (make_technique_params).
struct TechniqueParams {
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< fixes the depth code's bits (SPEC 2)
  std::uint32_t payload_bits = 32;               ///< 32 for L64, 0 for L32 (data stored as 0)
  Extent screen;  ///< V, in pixels
  std::uint32_t pool_capacity = 0;  ///< linked lists: nodes
  std::uint32_t layers = HABUFFER_DEFAULT_LAYERS;  ///< fixed arrays, k-buffer: K
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;  ///< sorted lists: steps of one insertion
  float cull_tau = 0.0f;                             ///< sorted lists: early termination (0: off)
  bool saturation = false;                           ///< sorted lists: saturation depth
  bool occupancy = false;                            ///< k-buffer: occupancy-map culling
  std::uint32_t occupancy_words = HABUFFER_DEFAULT_OCCUPANCY_WORDS;  ///< k-buffer: 32-bit occupancy words per pixel
  std::uint32_t occupancy_near_code = 0;   ///< k-buffer: the depth code of depth_range.near_t
  std::uint32_t occupancy_bucket_codes = 1;  ///< k-buffer: depth codes per occupancy bucket
  DepthRange depth_range;                    ///< wboit's weights
};

/// The occupancy buckets' integer geometry over the depth codes of `range`
/// (exact on both paths): bucket 0 holds near_t, the last one far_t.
void occupancy_geometry(const TechniqueConfig& c, std::uint32_t& near_code, std::uint32_t& bucket_codes);

/// The kernels' parameters for configuration `c`; throws std::invalid_argument
/// for age bits outside 4..12.
inline TechniqueParams make_technique_params(const TechniqueConfig& c) {
  TechniqueParams p;
  p.age_bits = c.buffer.age_bits;
  p.payload_bits = c.buffer.layout == Layout::L64 ? 32 : 0;
  p.screen = c.buffer.screen;
  p.pool_capacity = static_cast<std::uint32_t>(c.pool_capacity);
  p.layers = c.layers;
  p.iter_limit = c.buffer.iter_limit;
  p.cull_tau = c.buffer.early_cull_tau;
  p.saturation = c.buffer.saturation;
  p.occupancy = c.occupancy;
  p.occupancy_words = c.occupancy_words;
  occupancy_geometry(c, p.occupancy_near_code, p.occupancy_bucket_codes);
  p.depth_range = c.depth_range;
  return p;
}

}  // namespace habuffer
