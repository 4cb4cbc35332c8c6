// The fence around third-party readers (habuffer/fenced_call.h, issue 46):
// what a forked child costs with nothing to read and beside a parent holding
// resident memory (its page tables are copied), and a voxel sphere loaded
// from a VDB file (OpenVDB's reader in the child) against the same grid
// from a HAVOXEL1 file (read in the process). docs/performance.md,
// "Fenced readers".
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "habuffer/fenced_call.h"
#include "habuffer/render/voxel_vdb.h"
#include "habuffer/render/voxelizer.h"

namespace {

using namespace habuffer;

// A fenced call that reads nothing, beside `state.range(0)` MiB the parent
// has touched (resident, so fork copies their page tables).
void BM_FencedCallEmpty(benchmark::State& state) {
  std::vector<std::uint8_t> resident(static_cast<std::size_t>(state.range(0)) << 20);
  for (std::size_t i = 0; i < resident.size(); i += 4096) resident[i] = 1;
  benchmark::DoNotOptimize(resident.data());
  for (auto _ : state) benchmark::DoNotOptimize(fenced_call("bench", [] { return std::string("ok"); }));
}
BENCHMARK(BM_FencedCallEmpty)->ArgName("parent_MiB")->Arg(0)->Arg(256)->Arg(1024)->Unit(benchmark::kMicrosecond);

// A ball of radius n/2 - 1 in an n^3 grid, written as VDB and as HAVOXEL1.
struct SphereFiles {
  std::string vdb, grid;
  explicit SphereFiles(std::uint32_t n) {
    VoxelGrid g(n, Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)});
    const double c = (n - 1) / 2.0, r = n / 2.0 - 1.0;
    for (std::uint32_t z = 0; z < n; ++z)
      for (std::uint32_t y = 0; y < n; ++y)
        for (std::uint32_t x = 0; x < n; ++x)
          if ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) <= r * r) g.set(x, y, z);
    const std::string base = (std::filesystem::temp_directory_path() / ("habuffer_bench_sphere" + std::to_string(n))).string();
    vdb = base + ".vdb";
    grid = base + ".grid";
    save_voxel_vdb(vdb, g);
    save_voxel_grid(grid, g);
  }
  ~SphereFiles() {
    std::remove(vdb.c_str());
    std::remove(grid.c_str());
  }
};

void BM_LoadVoxelFile(benchmark::State& state) {
  if (!has_vdb_support()) {
    state.SkipWithError("built without OpenVDB");
    return;
  }
  const SphereFiles files(static_cast<std::uint32_t>(state.range(0)));
  const std::string& path = state.range(1) != 0 ? files.vdb : files.grid;
  for (auto _ : state) benchmark::DoNotOptimize(read_voxel_file(path).count());
  state.SetLabel(state.range(1) != 0 ? "vdb (fenced OpenVDB)" : "havoxel1 (in process)");
}
BENCHMARK(BM_LoadVoxelFile)
    ->ArgNames({"side", "vdb"})
    ->Args({64, 0})->Args({64, 1})->Args({256, 0})->Args({256, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
