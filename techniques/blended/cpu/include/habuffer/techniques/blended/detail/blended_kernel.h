/// @file
/// Weighted blended OIT and plain blending on the CPU: the shared GLSL of
/// techniques/blended/cpu/include/habuffer/techniques/blended/blended.glsl compiled as member functions.
#pragma once

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The blended baselines' accumulation and resolve (blended.glsl) as member
/// functions; it holds no buffers: the caller keeps the accumulators.
class BlendedKernel : public KernelUniforms {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The word ha_record.glsl packs records in: 64 bits.
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;  ///< bits of ha_word

  /// Reads the record layout and the depth range from `uniforms` (technique_params.h).
  explicit BlendedKernel(const KernelUniforms& uniforms) : KernelUniforms(uniforms) {}

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/techniques/blended/blended.glsl"
};

}  // namespace habuffer
