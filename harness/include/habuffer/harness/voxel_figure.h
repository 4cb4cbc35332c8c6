/// @file
/// Issue 21's voxelization table as a harness run: meshes x grid sizes
/// (128^3, 256^3, 512^3 by default), each voxelized (habuffer/render/
/// voxelizer.h) and checked against the ray-parity reference: time, memory
/// of the lists against the dense bit grid, crossings, odd columns, merged
/// crossings, mismatches outside the near-surface band and the band.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "habuffer/harness/result_table.h"
#include "habuffer/render/voxelizer.h"

namespace habuffer::harness {

/// What the voxelization table runs.
struct VoxelFigureSettings {
  std::vector<std::string> meshes{"sphere", "torus", "wuson", "spider"};  ///< solids (sphere, torus, box) or scenes
  std::vector<std::uint32_t> grids{128, 256, 512};                       ///< voxels per side
  VoxelAxis axis = VoxelAxis::Z;
  bool cpu = false;               ///< the lists built on the CPU (voxelize's cpu)
  std::uint32_t repeats = 3;      ///< voxelizations per row (median time)
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (rows done, rows)
};

/// A mesh word as voxelize takes it: sphere, torus and box are the closed
/// solids of habuffer/solids.h, anything else a catalog scene or mesh file.
Scene voxel_mesh(const std::string& word);

/// The table (one row per mesh and grid). Needs a current OpenGL 4.5
/// context. Throws std::invalid_argument (settings), SceneError (a mesh).
ResultTable run_voxel_figure(const VoxelFigureSettings& settings);

}  // namespace habuffer::harness
