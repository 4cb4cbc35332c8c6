/// @file
/// Solid voxelization on sorted depth lists (seed 000, sections 2.2 and
/// 6.3): the mesh rasterized orthographically along one axis at N x N into
/// an HA-buffer, every pixel's list holding each crossing of the surface
/// with its facing, and a voxel solid iff an odd number of crossings lie
/// nearer than its centre ((k + 1/2) / N along the axis).
///
/// Records are L64: the depth code, and the facing in the data word (1 front,
/// 2 back), so an entry and an exit at one depth stay two records (touching
/// solids: one's exit and the other's entry both count, and the parity
/// between them is right); two crossings of one facing at one code are equal
/// records and merge (SPEC 10), which flips the parity behind them: they are
/// counted (VoxelStats::merged, the build's duplicates) and reported. The
/// build is lossless: the table grows until nothing is dropped, and a
/// voxelization that still lost a crossing throws rather than return a grid
/// with wrong columns.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/fragment.h"
#include "habuffer/scene.h"

namespace habuffer {

/// The axis the views look along.
enum class VoxelAxis { X, Y, Z };
/// "x", "y", "z".
std::string to_string(VoxelAxis a);

/// N x N x N voxels over a box, one bit each.
struct VoxelGrid {
  std::uint32_t n = 0;  ///< voxels per side
  Bounds box;           ///< the region the grid spans (voxel (x, y, z) is the box's cell of that index)
  std::vector<std::uint64_t> words;  ///< bit x + n (y + n z), 64 to a word

  /// An empty grid of `n` per side over `box`. Throws std::invalid_argument for n outside 1..4096.
  VoxelGrid(std::uint32_t n, Bounds box);
  VoxelGrid() = default;
  [[nodiscard]] bool solid(std::uint32_t x, std::uint32_t y, std::uint32_t z) const;
  void set(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool solid = true);
  /// Solid voxels.
  [[nodiscard]] std::uint64_t count() const;
  /// Bytes of the bits: n^3 / 8 rounded up to words.
  [[nodiscard]] std::uint64_t memory_bytes() const { return words.size() * 8; }
};

/// What voxelize runs with.
struct VoxelizeSettings {
  std::uint32_t grid = 128;      ///< voxels per side N (the views' N x N pixels)
  VoxelAxis axis = VoxelAxis::Z; ///< the axis the views look along
  std::optional<Bounds> box;     ///< the grid's region; default: the scene's bounding box
  /// Gl: the lists built on the GPU; Cpu: GL only rasterizes and captures
  /// the crossings, the lists are built on the CPU (the same lists, so the
  /// same grid: tested).
  bool cpu = false;
  std::uint32_t threads = 0;     ///< the CPU path's worker threads (0: the default)
  /// Throws std::invalid_argument naming the field (grid outside 1..4096, an
  /// empty or flat box).
  void validate() const;
};

/// What a voxelization measured.
struct VoxelStats {
  Counters counters;               ///< the final gather's outcomes (duplicates: merged crossings)
  std::uint64_t merged = 0;        ///< crossings merged with an equal one (same facing, same code): parity at risk
  std::uint32_t attempts = 0;      ///< gathers (the table grown until nothing was dropped)
  std::uint64_t table_slots = 0;   ///< the final table's slots
  double load_factor = 0.0;        ///< stored / slots
  std::uint64_t list_bytes = 0;    ///< the HA-buffer's storage
  double gather_ms = 0.0, parity_ms = 0.0;  ///< the GPU gather(s), and the parity walk on the CPU
  /// Columns with an odd number of crossings: a closed surface gives none,
  /// so these say the mesh is not watertight (or a crossing merged).
  std::uint64_t odd_columns = 0;
};

/// A voxelization: the grid and its stats.
struct Voxelization {
  VoxelGrid grid;
  VoxelStats stats;
};

/// Voxelizes every mesh of `scene` (see the file comment). Needs a current
/// OpenGL 4.5 core context with 64-bit shader integers. Throws
/// std::invalid_argument (settings), SceneError (an empty scene), GlError
/// (the context's limits, or crossings lost after every growth).
Voxelization voxelize(const Scene& scene, const VoxelizeSettings& settings);

/// Three-axis voting for meshes that are not watertight: voxelize along x,
/// y and z and keep a voxel solid where at least two of the three agree. It
/// fixes voxels that only one axis's column reaches through a hole (a missing
/// triangle, a crack); it does not fix a hole two axes see, nor make a
/// self-intersecting or inside-out mesh consistent. `settings.axis` is
/// ignored; the stats add the three voxelizations' counters, times and odd
/// columns.
Voxelization voxelize_voting(const Scene& scene, const VoxelizeSettings& settings);

/// The grid file: 8 bytes "HAVOXEL1", u32 N, u32 0 (reserved), six float32
/// (the box's lo x y z, hi x y z), then ceil(N^3 / 64) u64 words, bit i of
/// the grid at bit i % 64 of word i / 64 (i = x + N (y + N z)), all
/// little-endian. Written whole or not at all (habuffer/atomic_file.h);
/// throws DataError naming the path.
void save_voxel_grid(const std::string& path, const VoxelGrid& grid);
/// The grid as NRRD (teem's "nearly raw raster data", NRRD0004: a text
/// header, then N^3 uint8 voxels, 1 solid, x fastest, raw), the field's
/// volume format: read by teem's `unu` (Debian `teem-apps`), VTK's
/// vtkNrrdReader and so ParaView, ITK, 3D Slicer and pynrrd. The header's
/// `space origin` is voxel (0, 0, 0)'s centre and `space directions` the
/// voxel's size along x, y and z, so readers place it in the mesh's space.
/// `comment` goes on a `#` line (newlines replaced). Written whole or not
/// at all; throws DataError naming the path.
void save_voxel_nrrd(const std::string& path, const VoxelGrid& grid, const std::string& comment = "");
/// Reads a grid file; throws DataError naming the path and what is wrong
/// (magic, N outside 1..4096, a size that does not match, a bad box).
VoxelGrid load_voxel_grid(const std::string& path);
/// The same for a file's bytes already read (`path` names them in messages).
VoxelGrid parse_voxel_grid(const std::string& bytes, const std::string& path);

/// The exact reference: each column's ray along the axis through its centre
/// intersected with every triangle in double, a voxel solid iff an odd
/// number of crossings lie before its centre. `band` (when given) receives,
/// per voxel, whether it lies near the surface: a crossing within
/// `band_depth` voxels of its centre along the column, or a parity that
/// differs on a ray 1/512 voxel beside the column's along either axis
/// across it (the rasterizer snaps each coordinate to the nearest 1/256
/// pixel: an edge or a steep face that moves across the centre within that
/// snapping is the rasterizer's to decide).
VoxelGrid voxel_reference(const Scene& scene, const VoxelizeSettings& settings, std::vector<bool>* band = nullptr,
                          double band_depth = 1e-3);

/// A grid against voxel_reference: voxels that differ outside the band, and the band's size.
struct VoxelCheck {
  std::uint64_t mismatches = 0, band = 0;
};
/// Compares `grid` (voxelized with `settings`) with voxel_reference.
VoxelCheck check_voxels(const Scene& scene, const VoxelizeSettings& settings, const VoxelGrid& grid);
/// Compares a three-axis vote (voxelize_voting) with the same vote of the
/// three axes' references, two of three; the band is every voxel in any
/// axis's band (`settings.axis` is ignored).
VoxelCheck check_voxels_voting(const Scene& scene, const VoxelizeSettings& settings, const VoxelGrid& grid);

}  // namespace habuffer
