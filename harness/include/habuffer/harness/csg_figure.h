/// @file
/// Issue 21's CSG curve as a harness run: a cube minus 1, 2, 4, ... 512
/// cylinders on a grid through it, rendered from lossless sorted lists
/// (habuffer/render/csg_renderer.h): time, records, memory, and the pixels
/// that differ from the ray caster outside its edge band.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/harness/result_table.h"
#include "habuffer/scene.h"

namespace habuffer::harness {

/// A cube [-1, 1]^3 minus `cylinders` cylinders along z on a square grid
/// through it: the primitives (the cube first), their names and the expression.
struct CsgCylinders {
  Scene scene;
  std::vector<std::string> names;
  std::string expression;  ///< "cube - (c0 | c1 | ...)"
};
/// See CsgCylinders; throws std::invalid_argument for 0 or more than 4095 cylinders.
CsgCylinders csg_cylinders(std::uint32_t cylinders);

/// What the curve runs.
struct CsgFigureSettings {
  std::vector<std::uint32_t> cylinders{1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
  Extent size{128, 128};
  bool cpu = false;           ///< the lists built on the CPU
  std::uint32_t repeats = 3;  ///< renders per point (median time)
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (points done, points)
};

/// The curve, one row per cylinder count. Needs a current OpenGL 4.5 context.
ResultTable run_csg_figure(const CsgFigureSettings& settings);

}  // namespace habuffer::harness
