/// @file
/// Heat maps of per-pixel quantities (depth complexity, max age, culled
/// fragments) through OpenImageIO's colour maps, with a legend strip under
/// the image: the colour ramp, its range and a title.
#pragma once

#include <span>
#include <string>

#include "habuffer/extent.h"

namespace habuffer {

/// The smallest and largest value a heat map was given.
struct HeatmapRange {
  double min = 0.0, max = 0.0;  ///< both 0 for no values
};

/// Writes the heat map of `values` (size.area() of them) to `path` with OpenImageIO's colour map `colour_map`.
/// values: row-major, row 0 at the bottom (OpenGL's order). Colours span
/// [0, max]; returns the range of the values. Legend text needs a TrueType
/// font OpenImageIO finds (DejaVu on Debian); without one the strip has the
/// ramp only. Throws ImageError naming the file.
HeatmapRange write_heatmap(const std::string& path, Extent size, std::span<const float> values, const std::string& title,
                           const std::string& colour_map = "inferno");

}  // namespace habuffer
