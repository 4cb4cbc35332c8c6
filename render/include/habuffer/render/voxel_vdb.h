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
///
/// Reading is fenced (issue 46): the file is read once through the bounded
/// reader (a FIFO or a pipe is read, never reopened), and OpenVDB parses the
/// bytes in a child process (habuffer/fenced_call.h), which hands back the
/// solid voxels sparse: 8^3 blocks and solid boxes (OpenVDB's tiles). A
/// corrupt file that makes OpenVDB's reader abort is one DataError, and no
/// grid is expanded before its size is known: a caller that needs keys
/// reads them from the sparse form (a 1024^3 tile in a 500-byte file is
/// 2^30 voxels, counted before anything is allocated; two voxels 4095 apart
/// are two keys, not an 8 GiB dense grid).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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
/// Whether `bytes` begin with OpenVDB's magic number.
bool is_vdb_bytes(const std::string& bytes);

/// A grid's solid voxels kept sparse (see the file comment): the grid's side
/// and box, 8^3 blocks (bit x + 8 (y + 8 z) of `bits` is voxel origin + (x, y,
/// z)) and solid boxes, every solid voxel inside [0, n)^3 and in exactly one
/// of them.
struct SparseVoxels {
  struct Block {
    std::array<std::int32_t, 3> origin{};  ///< may lie below 0: only the set bits are voxels
    std::array<std::uint64_t, 8> bits{};
  };
  struct Box {
    std::array<std::uint32_t, 3> lo{}, hi{};  ///< inclusive
  };
  std::uint32_t n = 0;
  Bounds box;
  std::vector<Block> blocks;
  std::vector<Box> boxes;
  /// A HAVOXEL1 file's bits as read (the file was dense already); empty (n
  /// 0) for a VDB file.
  VoxelGrid bits;

  /// Solid voxels (counted, nothing expanded).
  [[nodiscard]] std::uint64_t count() const;
  /// Calls `visit(x, y, z)` for every solid voxel, blocks first.
  template <class Visit>
  void for_each(Visit visit) const {
    for (std::uint64_t w = 0; w < bits.words.size(); ++w)
      for (std::uint64_t word = bits.words[w]; word != 0; word &= word - 1) {
        const std::uint64_t i = w * 64 + static_cast<std::uint64_t>(__builtin_ctzll(word));
        const std::uint64_t n2 = std::uint64_t{bits.n} * bits.n;
        visit(static_cast<std::uint32_t>(i % bits.n), static_cast<std::uint32_t>(i / bits.n % bits.n),
              static_cast<std::uint32_t>(i / n2));
      }
    for (const Block& b : blocks)
      for (std::uint32_t i = 0; i < 512; ++i)
        if ((b.bits[i / 64] >> (i % 64)) & 1u)
          visit(static_cast<std::uint32_t>(b.origin[0] + static_cast<std::int32_t>(i % 8)),
                static_cast<std::uint32_t>(b.origin[1] + static_cast<std::int32_t>(i / 8 % 8)),
                static_cast<std::uint32_t>(b.origin[2] + static_cast<std::int32_t>(i / 64)));
    for (const Box& b : boxes)
      for (std::uint32_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::uint32_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::uint32_t x = b.lo[0]; x <= b.hi[0]; ++x) visit(x, y, z);
  }
  /// The dense grid (n^3 bits), its bytes checked against this machine's
  /// memory first: DataError naming `path`, the side and the bytes.
  [[nodiscard]] VoxelGrid dense(const std::string& path) const;
};

/// A voxel grid file of either format, read once (a pipe included) and told
/// by its first bytes: HAVOXEL1 or OpenVDB (fenced). DataError naming the
/// file and the reason.
SparseVoxels read_voxel_file(const std::string& path);
/// read_voxel_file's grid, dense.
VoxelGrid load_voxel_file(const std::string& path);
/// The same for bytes already read (`path` names them in messages).
SparseVoxels parse_voxel_bytes(const std::string& bytes, const std::string& path);
/// OpenVDB bytes parsed in a fenced child (see the file comment).
SparseVoxels parse_vdb_bytes(const std::string& bytes, const std::string& path);

}  // namespace habuffer
