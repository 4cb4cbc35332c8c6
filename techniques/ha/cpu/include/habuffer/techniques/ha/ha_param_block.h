/// @file
/// The HA-buffer's part of the GPU paths' parameter block (ha_params.h), the
/// one writer the OpenGL and Vulkan tables share.
#pragma once

#include <cstdint>

#include "habuffer/buffer_config.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// Cells of the max-age table of `c`'s screen, one per B x B block.
std::uint64_t ha_max_age_cells(const BufferConfig& c);

/// The HA-buffer's fields of `p` for `c` (its table, which must be set):
/// table size, age and coverage bits, block, cells per row, probe limit,
/// early cull and saturation.
void write_ha_params(const BufferConfig& c, ParamBlock& p);

}  // namespace habuffer
