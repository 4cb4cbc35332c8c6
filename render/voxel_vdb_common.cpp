// What both builds share: telling a VDB file by its magic number, and the
// loader that picks the format by content.
#include <cstdint>
#include <fstream>

#include "habuffer/render/voxel_vdb.h"

namespace habuffer {

bool is_vdb_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[4] = {};
  if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
  // OpenVDB's magic, the int32 0x56444220 ("VDB "), little-endian.
  return b[0] == 0x20 && b[1] == 0x42 && b[2] == 0x44 && b[3] == 0x56;
}

VoxelGrid load_voxel_file(const std::string& path) {
  return is_vdb_file(path) ? load_voxel_vdb(path) : load_voxel_grid(path);
}

}  // namespace habuffer
