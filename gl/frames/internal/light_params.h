// What a frame driver told its light (GlFrameOptions::light) writes into the
// module: the define that declares habuffer_insert_light, and the parameter
// block's light fields (habuffer/gl/light_mapping.h).
#pragma once

#include <optional>
#include <string>

#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/light_mapping.h"

namespace habuffer::gl {

/// "#define HABUFFER_LIGHT_GATHER\n" for a driver told its light, else empty:
/// without it the module refuses habuffer_insert_light at compile time.
std::string light_module_defines(const std::optional<GlLightMapping>& light);

/// The block's light fields: with `light`, habuffer_light_gather 1, its near
/// and far, and its depth map under the window mapping `recorded` at the last
/// frame (the default one before the first); without, all zero. Throws as
/// light_depth_map.
void write_light_params(const std::optional<GlLightMapping>& light, const std::optional<GlGatherDepth>& recorded,
                        GlParams& params);

/// What a frame with `options` gathers (GlGatherDepth), the window mapping
/// read from the current context.
GlGatherDepth gather_depth_now(const GlFrameOptions& options);

}  // namespace habuffer::gl
