/// @file
/// The exact reference of SPEC 7: every valid fragment of a pixel, fully
/// sorted by unquantized depth (nearest first, ties by larger data first),
/// composited front to back in double precision, with no cull and no loss.
/// On a multisampled screen (`samples` 2, 4 or 8) each sample composites
/// the fragments whose coverage word names it (0: every sample) and the
/// pixel is the mean of its samples (issue 37's per-sample reference).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"

namespace habuffer {

/// Every pixel over one `background` (row-major, screen.area() entries); invalid
/// fragments are left out. Throws std::out_of_range for a fragment off the
/// screen, std::invalid_argument for samples other than 1, 2, 4 or 8.
std::vector<glm::dvec4> reference_composite(std::span<const Fragment> fragments, Extent screen,
                                            glm::dvec3 background, std::uint32_t samples = 1);
/// Each pixel over its own background (row-major, screen.area() entries).
std::vector<glm::dvec4> reference_composite(std::span<const Fragment> fragments, Extent screen,
                                            std::span<const glm::vec3> backgrounds, std::uint32_t samples = 1);

}  // namespace habuffer
