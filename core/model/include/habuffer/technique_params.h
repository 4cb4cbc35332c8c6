/// @file
/// The "uniforms" of every technique's kernel, declared once: the GPU path's
/// parameter block of shared/ha_params.h (the std140 uniform block every
/// GLSL module reads) as a C++ struct, ParamBlock. The node lists', arrays'
/// and k-buffer's CPU kernels derive from it (KernelUniforms), so the shared
/// GLSL reads the same members under the same names on both paths, and one
/// function writes a configuration's fields into it for both
/// (write_technique_params). HashKernel is the exception: it keeps members of
/// its own under the GLSL's names, written from KernelParams, because the
/// spatial hash runs the same probe with parameters that are no technique's;
/// the harness's traced kernels (harness/traced_kernels.h) copy HashKernel's
/// members for the same reason.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec2.hpp>

#include "habuffer/technique.h"
#include "habuffer/shared/ha_constants.h"

namespace habuffer {

#define HABUFFER_PARAMS_BEGIN struct ParamBlock {
#define HABUFFER_PARAMS_END };
#define HABUFFER_PARAM_UINT(name) std::uint32_t name = 0;
#define HABUFFER_PARAM_FLOAT(name) float name = 0.0f;
#define HABUFFER_PARAM_UVEC2(name) glm::uvec2 name{0u, 0u};
#include "habuffer/shared/ha_params.h"
#undef HABUFFER_PARAMS_BEGIN
#undef HABUFFER_PARAMS_END
#undef HABUFFER_PARAM_UINT
#undef HABUFFER_PARAM_FLOAT
#undef HABUFFER_PARAM_UVEC2

static_assert(sizeof(glm::uvec2) == 8, "the block's uvec2 members are two 32-bit words (std140)");
static_assert(offsetof(ParamBlock, ha_table_size) % 8 == 0 && offsetof(ParamBlock, habuffer_screen_size) % 8 == 0,
              "std140 aligns uvec2 to 8 bytes: keep every uvec2 of shared/ha_params.h at a multiple of 8");
static_assert(sizeof(ParamBlock) % 16 == 0,
              "std140 rounds a block to 16 bytes: pad shared/ha_params.h with ha_unused_N members");

/// What a CPU kernel reads besides its buffers: the parameter block, and the
/// record word's payload bits, which a GLSL module gets as a constant of its
/// atomic mode rather than in the block.
struct KernelUniforms : ParamBlock {
  std::uint32_t ha_payload_bits = 32;  ///< 32 for L64, 0 for L32 (data stored as 0)
};

/// The occupancy buckets' integer geometry over the depth codes of `range`
/// (exact on both paths): bucket 0 holds near_t, the last one far_t.
void occupancy_geometry(const TechniqueConfig& c, std::uint32_t& near_code, std::uint32_t& bucket_codes);

/// Writes what configuration `c` fixes of the block for the technique
/// kernels: age bits, pool, layers, iteration limit, early cull, saturation,
/// occupancy map and its geometry, depth range. The screen and the frame's
/// fields (capture, deferred calls, gather phase) are the frame driver's,
/// the HA-buffer's table fields its own.
void write_technique_params(const TechniqueConfig& c, ParamBlock& p);

/// The CPU kernels' uniforms for `c`: write_technique_params, the screen and
/// the payload bits.
KernelUniforms kernel_uniforms(const TechniqueConfig& c);

}  // namespace habuffer
