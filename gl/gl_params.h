// The parameter block of core/include/habuffer/shared/ha_params.h as a C++ struct (std140
// layout: the block's only vectors are uvec2 at offsets that are multiples
// of 8, checked below).
#pragma once

#include <cstddef>
#include <cstdint>

namespace habuffer::gl {

#define HABUFFER_PARAMS_BEGIN struct GlParams {
#define HABUFFER_PARAMS_END };
#define HABUFFER_PARAM_UINT(name) std::uint32_t name = 0;
#define HABUFFER_PARAM_FLOAT(name) float name = 0.0f;
#define HABUFFER_PARAM_UVEC2(name) std::uint32_t name[2] = {0, 0};
#include "habuffer/shared/ha_params.h"
#undef HABUFFER_PARAMS_BEGIN
#undef HABUFFER_PARAMS_END
#undef HABUFFER_PARAM_UINT
#undef HABUFFER_PARAM_FLOAT
#undef HABUFFER_PARAM_UVEC2

static_assert(offsetof(GlParams, ha_table_size) % 8 == 0 && offsetof(GlParams, ha_screen_size) % 8 == 0,
              "std140 aligns uvec2 to 8 bytes");
static_assert(sizeof(GlParams) % 16 == 0, "std140 rounds a block to 16 bytes");

}  // namespace habuffer::gl
