/// @file
/// Weighted blended OIT and plain blending on the CPU: the shared GLSL of
/// core/include/habuffer/shared/ha_blended.glsl compiled as member functions.
#pragma once

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

class BlendedKernel {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;

  explicit BlendedKernel(const TechniqueParams& params)
      : ha_age_bits(params.age_bits),
        ha_payload_bits(params.payload_bits),
        ha_depth_near(params.depth_range.near_t),
        ha_depth_far(params.depth_range.far_t) {}

  uint ha_age_bits;
  uint ha_payload_bits;
  float ha_depth_near;
  float ha_depth_far;

#include "shared/ha_record.glsl"
#include "shared/ha_blend.glsl"
#include "shared/ha_blended.glsl"
};

}  // namespace habuffer
