// A build without OpenVDB (HABUFFER_WITH_OPENVDB off or not found): the VDB
// files are refused by name.
#include "habuffer/data_error.h"
#include "habuffer/render/voxel_vdb.h"

namespace habuffer {
namespace {

[[noreturn]] void refuse(const std::string& path) {
  throw DataError(path + ": OpenVDB files need a habuffer built with OpenVDB (Debian libopenvdb-dev)");
}

}  // namespace

bool has_vdb_support() { return false; }
std::string vdb_support() { return "none (built without OpenVDB)"; }
void save_voxel_vdb(const std::string& path, const VoxelGrid&, const std::string&) { refuse(path); }
SparseVoxels parse_vdb_bytes(const std::string&, const std::string& path) { refuse(path); }

}  // namespace habuffer
