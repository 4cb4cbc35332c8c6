#include "habuffer/harness/voxel_figure.h"

#include <stdexcept>

#include "habuffer/harness/workload.h"
#include "habuffer/scene_catalog.h"
#include "habuffer/solids.h"

namespace habuffer::harness {

Scene voxel_mesh(const std::string& word) {
  Scene s;
  s.name = word;
  if (word == "sphere") s.meshes = {sphere_mesh({0, 0, 0}, 1.0f)};
  else if (word == "torus") s.meshes = {torus_mesh({0, 0, 0}, 1.0f, 0.4f)};
  else if (word == "box") s.meshes = {box_mesh({0, 0, 0}, {1, 1, 1})};
  else return make_scene(word, {});
  return s;
}

ResultTable run_voxel_figure(const VoxelFigureSettings& f) {
  if (f.meshes.empty() || f.grids.empty()) throw std::invalid_argument("the voxel table needs a mesh and a grid size");
  if (f.repeats == 0) throw std::invalid_argument("--repeats must be at least 1");
  ResultTable table;
  table.title = "voxels";
  const std::uint64_t total = f.meshes.size() * f.grids.size();
  std::uint64_t done = 0;
  for (const std::string& word : f.meshes) {
    const Scene scene = voxel_mesh(word);
    for (const std::uint32_t n : f.grids) {
      VoxelizeSettings s;
      s.grid = n;
      s.axis = f.axis;
      s.cpu = f.cpu;
      std::vector<double> ms;
      Voxelization v;
      for (std::uint32_t rep = 0; rep < f.repeats; ++rep) {
        v = voxelize(scene, s);
        ms.push_back(v.stats.gather_ms + v.stats.parity_ms);
      }
      const VoxelCheck check = check_voxels(scene, s, v.grid);
      const std::uint64_t mismatches = check.mismatches, in_band = check.band;
      const Spread t = spread_of(ms);
      const double voxels = static_cast<double>(n) * n * n;
      ResultRow row;
      row.set("mesh", word).set("grid", n).set("axis", to_string(f.axis)).set("path", f.cpu ? "cpu" : "gl");
      row.set("voxels", v.grid.count()).set("crossings", v.stats.counters.fragments).set("merged", v.stats.merged)
          .set("odd_columns", v.stats.odd_columns).set("ms", t.median).set("ms_min", t.min).set("ms_max", t.max)
          .set("gather_ms", v.stats.gather_ms).set("parity_ms", v.stats.parity_ms)
          .set("list_bytes", v.stats.list_bytes).set("dense_bytes", v.grid.memory_bytes())
          .set("load_factor", v.stats.load_factor).set("mismatches", mismatches).set("band", in_band)
          .set("band_fraction", static_cast<double>(in_band) / voxels);
      table.rows.push_back(row);
      if (f.on_progress) f.on_progress(++done, total);
    }
  }
  table.notes["ms"] = "one voxelization: the gather (GPU, or capture and CPU build) and the CPU parity walk; median of "
                      "--repeats";
  table.notes["mismatches"] = "voxels that differ from the ray-parity reference outside its near-surface band "
                              "(habuffer/render/voxelizer.h)";
  table.notes["odd_columns"] = "columns crossed an odd number of times: the mesh is not watertight there";
  return table;
}

}  // namespace habuffer::harness
