/// @file
/// Weighted blended OIT and plain blending on the CPU: the shared GLSL of
/// core/include/habuffer/techniques/blended/ha_blended.glsl compiled as member functions.
#pragma once

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The blended baselines' accumulation and resolve (ha_blended.glsl) as member
/// functions; it holds no buffers: the caller keeps the accumulators.
class BlendedKernel {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The word ha_record.glsl packs records in: 64 bits.
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;  ///< bits of ha_word

  /// Reads the record layout and the depth range from `params`.
  explicit BlendedKernel(const TechniqueParams& params)
      : ha_age_bits(params.age_bits),
        ha_payload_bits(params.payload_bits),
        ha_depth_near(params.depth_range.near_t),
        ha_depth_far(params.depth_range.far_t) {}

  uint ha_age_bits;  ///< A, the age bits that fix the depth code (SPEC 2)
  uint ha_payload_bits;  ///< 32 for L64, 0 for L32
  float ha_depth_near;  ///< depth_range.near_t (wboit's weight is normalized to the range)
  float ha_depth_far;  ///< depth_range.far_t

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/techniques/blended/ha_blended.glsl"
};

}  // namespace habuffer
