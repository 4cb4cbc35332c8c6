// libFuzzer target: voxel grid files, HAVOXEL1 and OpenVDB
// (habuffer/render/voxel_vdb.h). Any input must either parse or raise
// DataError; never crash, hang, or take the process down: OpenVDB's reader,
// which aborts on some corrupt files, runs fenced in a child process
// (habuffer/fenced_call.h), so this target checks the fence holds rather than
// guiding the search through OpenVDB (the child's coverage is not the
// fuzzer's). A grid that parses holds its voxels inside its side, counted
// as they are visited.
#include <cstddef>
#include <cstdint>
#include <string>

#include "habuffer/data_error.h"
#include "habuffer/render/voxel_vdb.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace habuffer;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const SparseVoxels v = parse_voxel_bytes(bytes, "fuzz.vdb");
    if (v.n == 0 || v.n > 4096) __builtin_trap();
    const std::uint64_t count = v.count();
    if (count > (1u << 22)) return 0;  // a large tile: counted, not walked here
    std::uint64_t seen = 0;
    v.for_each([&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
      if (x >= v.n || y >= v.n || z >= v.n) __builtin_trap();
      ++seen;
    });
    if (seen != count) __builtin_trap();
  } catch (const DataError&) {
  }
  return 0;
}
