/// @file
/// Voxel grids as OpenVDB files, so the field's tools (Blender, Houdini,
/// OpenVDB's own vdb_view and vdb_print) open voxelize's grids without a
/// conversion. Optional at build time (HABUFFER_WITH_OPENVDB, Debian
/// libopenvdb-dev): without it has_vdb_support() is false and both functions
/// throw DataError naming the file and the reason.
///
/// The file: one openvdb::BoolGrid named "solid", class "fog volume" is not
/// claimed (a BoolGrid has no class), every solid voxel active and true, at
/// index (x, y, z) of the grid; the transform places index (x, y, z) at the
/// centre of the mesh-space cell it stands for (scale: the cell's size per
/// axis, translation: box.lo plus half a cell), so the grid lies where the
/// mesh does. Metadata keep habuffer's own side and box ("habuffer_side",
/// "habuffer_box_lo", "habuffer_box_hi"), so a grid read back is the grid
/// written, bit for bit.
///
/// Reading takes the grid named "solid", or the file's only grid; a BoolGrid
/// (active and true voxels) or a FloatGrid fog volume (active voxels of
/// value above 0). Level sets are refused (their inside is not stored as
/// active voxels: convert them to a fog volume first). Without habuffer's
/// metadata the grid is the bounding cube of its active voxels, its box from
/// the transform, which must be a scale and translation (no rotation).
#pragma once

#include <string>

#include "habuffer/render/voxelizer.h"

namespace habuffer {

/// Whether this build reads and writes OpenVDB files.
bool has_vdb_support();
/// "OpenVDB 10.0.1", or "none (...)" without it.
std::string vdb_support();
/// Writes `grid` as described above, whole or not at all (a temporary file renamed over `path`).
void save_voxel_vdb(const std::string& path, const VoxelGrid& grid, const std::string& comment = "");
/// Reads a grid as described above; DataError naming the file and the reason.
VoxelGrid load_voxel_vdb(const std::string& path);
/// Whether `path` begins with OpenVDB's magic number (false for a file that cannot be read).
bool is_vdb_file(const std::string& path);
/// A voxel grid file of either format, told by its first bytes: HAVOXEL1
/// (load_voxel_grid) or OpenVDB (load_voxel_vdb).
VoxelGrid load_voxel_file(const std::string& path);

}  // namespace habuffer
