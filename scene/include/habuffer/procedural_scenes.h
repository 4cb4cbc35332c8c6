/// @file
/// Procedural stress scenes after the papers: depth complexity on demand,
/// without mesh files (make_scene calls these by name).
#pragma once

#include <cstdint>

#include "habuffer/scene_catalog.h"

namespace habuffer {

/// Thin random tubes inside the unit sphere: very high depth complexity.
Scene make_hairball(std::uint32_t tubes, std::uint64_t seed, float opacity);
/// The HA-buffer paper's Fig. 8: same-size quads at random depths seen
/// orthographically; spread pulls their centres together (0: exactly stacked).
Scene make_quads(std::uint32_t quads, float spread, std::uint64_t seed, float opacity);
/// Full-screen planes at evenly spaced depths, submitted front to back or back
/// to front (the guacamole paper's Fig. 10).
Scene make_planes(std::uint32_t planes, PlaneOrder order, float opacity);

}  // namespace habuffer
