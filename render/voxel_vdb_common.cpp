// What both builds share: telling a VDB file by its magic number, the sparse
// voxels and the loaders that read a file once and pick the format by content.
#include <bit>
#include <cstdint>
#include <fstream>
#include <stdexcept>

#include "habuffer/bounded_read.h"
#include "habuffer/data_error.h"
#include "habuffer/memory_budget.h"
#include "habuffer/render/voxel_vdb.h"

namespace habuffer {
namespace {

// The largest grid file: side 4096, 4096^3 bits (a VDB file of a grid that
// size is far smaller).
constexpr std::uint64_t kMaxVoxelFileBytes = 40 + std::uint64_t{4096} * 4096 * 4096 / 8;

bool vdb_magic(const unsigned char* b) {
  // OpenVDB's magic, the int32 0x56444220 ("VDB "), little-endian.
  return b[0] == 0x20 && b[1] == 0x42 && b[2] == 0x44 && b[3] == 0x56;
}

}  // namespace

bool is_vdb_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[4] = {};
  if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
  return vdb_magic(b);
}

bool is_vdb_bytes(const std::string& bytes) {
  return bytes.size() >= 4 && vdb_magic(reinterpret_cast<const unsigned char*>(bytes.data()));
}

std::uint64_t SparseVoxels::count() const {
  std::uint64_t c = bits.count();
  for (const Block& b : blocks)
    for (const std::uint64_t w : b.bits) c += static_cast<std::uint64_t>(std::popcount(w));
  for (const Box& b : boxes)
    c += std::uint64_t{b.hi[0] - b.lo[0] + 1} * (b.hi[1] - b.lo[1] + 1) * (b.hi[2] - b.lo[2] + 1);
  return c;
}

VoxelGrid SparseVoxels::dense(const std::string& path) const {
  if (bits.n != 0) return bits;
  const std::uint64_t bytes = (std::uint64_t{n} * n * n + 63) / 64 * 8;
  try {
    check_fits_in_memory(path + ": a dense grid of side " + std::to_string(n) + " (" + std::to_string(count()) +
                             " solid voxels)",
                         bytes);
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }
  VoxelGrid g(n, box);
  for_each([&](std::uint32_t x, std::uint32_t y, std::uint32_t z) { g.set(x, y, z); });
  return g;
}

SparseVoxels parse_voxel_bytes(const std::string& bytes, const std::string& path) {
  if (is_vdb_bytes(bytes)) return parse_vdb_bytes(bytes, path);
  SparseVoxels s;
  s.bits = parse_voxel_grid(bytes, path);
  s.n = s.bits.n;
  s.box = s.bits.box;
  return s;
}

SparseVoxels read_voxel_file(const std::string& path) {
  return parse_voxel_bytes(read_file_bounded(path, "voxel grid", kMaxVoxelFileBytes), path);
}

VoxelGrid load_voxel_file(const std::string& path) { return read_voxel_file(path).dense(path); }

VoxelGrid load_voxel_vdb(const std::string& path) {
  const std::string bytes = read_file_bounded(path, "OpenVDB file", kMaxVoxelFileBytes);
  if (!is_vdb_bytes(bytes)) throw DataError(path + ": not an OpenVDB file (no VDB magic number)");
  return parse_vdb_bytes(bytes, path).dense(path);
}

}  // namespace habuffer
