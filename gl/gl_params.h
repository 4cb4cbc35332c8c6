// The parameter block of core/shared/ha_params.h as a C++ struct (std140
// layout: the block's only vectors are uvec2 at offsets that are multiples
// of 8, checked below).
#pragma once

#include <cstddef>
#include <cstdint>

namespace habuffer::gl {

#define HA_PARAMS_BEGIN struct GlParams {
#define HA_PARAMS_END };
#define HA_PARAM_UINT(name) std::uint32_t name = 0;
#define HA_PARAM_FLOAT(name) float name = 0.0f;
#define HA_PARAM_UVEC2(name) std::uint32_t name[2] = {0, 0};
#include "../core/shared/ha_params.h"
#undef HA_PARAMS_BEGIN
#undef HA_PARAMS_END
#undef HA_PARAM_UINT
#undef HA_PARAM_FLOAT
#undef HA_PARAM_UVEC2

static_assert(offsetof(GlParams, ha_table_size) % 8 == 0 && offsetof(GlParams, ha_screen_size) % 8 == 0,
              "std140 aligns uvec2 to 8 bytes");
static_assert(sizeof(GlParams) % 16 == 0, "std140 rounds a block to 16 bytes");

}  // namespace habuffer::gl
