// habuffer voxelize: a mesh's solid voxels from lossless sorted depth lists
// (habuffer/render/voxelizer.h), with their stats, PNG slices and the
// ray-parity reference.
#include <cstdio>
#include <optional>

#include "commands.h"
#include "file_values.h"
#include "habuffer/atomic_folder.h"
#include "habuffer/csv.h"
#include "habuffer/file_roles.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/json_writer.h"
#include "habuffer/printable.h"
#include "habuffer/solid_check.h"
#include "habuffer/render/image.h"
#include "habuffer/render/voxel_vdb.h"
#include "habuffer/render/voxelizer.h"
#include "habuffer/scene_catalog.h"
#include "habuffer/harness/voxel_figure.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {

constexpr const char* kSliceMembers = "slice_*.png";

}  // namespace

const CommandSpec& voxelize_spec() {
  static const CommandSpec spec{
      "voxelize --mesh FILE|NAME --out GRID [--grid N] [--axis x|y|z|all] [--stats S.json] [OPTIONS]",
      {{"mesh", "FILE|NAME", "",
        "a closed mesh file, a catalog scene (engine, wuson, spider, ...) or a solid: sphere, torus, box", reads_in(mesh_file, "{}")},
       {"grid", "N", "128", "voxels per side, the grid fitted to the mesh's bounding box"},
       {"axis", "x|y|z|all", "z", "the views' axis; all: three-axis voting (for meshes that are not watertight)"},
       {"out", "GRID", "", "the grid file (HAVOXEL1: header, then N^3 bits; habuffer/render/voxelizer.h)", writes_creating_parents()},
       {"nrrd", "FILE", "", "the grid as NRRD too (uint8 0/1, placed in the mesh's space): ParaView, VTK, teem's unu", writes()},
       {"vdb", "FILE", "",
        "the grid as OpenVDB too (a BoolGrid 'solid', placed in the mesh's space): Blender, Houdini, vdb_view",
        writes()},
       {"stats", "S.json", "", "voxels, crossings, merged crossings, odd columns, memory, load, times", writes()},
       {"slices", "DIR", "", "one PNG per z layer of voxels (slice_0000.png, ...), solid white", writes_set(kSliceMembers)},
       {"reference", "", "",
        "compare with the ray-parity reference (with --axis all: its three axes' two-of-three vote): mismatches "
        "outside the near-surface band"},
       {"path", "gl|cpu", "gl", "where the lists are built: on the GPU, or captured and built on the CPU (same grid)"},
       {"threads", "N", "0", "(--path cpu) worker threads; 0: the default count"},
       {"quiet", "", "", "no summary"}},
      "  Exit codes: 0 ok (odd columns and merged crossings are warned about), 1 bad data, 2 bad usage.\n"};
  return spec;
}

namespace {

// The slices as one output set: swapped in whole over an earlier set (none
// of its members left behind), never mixed with it.
void write_slices(const std::string& dir, const VoxelGrid& g) {
  AtomicFolder set(dir, kSliceMembers);
  for (std::uint32_t z = 0; z < g.n; ++z) {
    Image image{{g.n, g.n}, std::vector<glm::vec4>(std::size_t{g.n} * g.n, glm::vec4(0, 0, 0, 1))};
    for (std::uint32_t y = 0; y < g.n; ++y)
      for (std::uint32_t x = 0; x < g.n; ++x)
        if (g.solid(x, y, z)) image.pixels[x + std::size_t{y} * g.n] = glm::vec4(1.0f);
    char name[32];
    std::snprintf(name, sizeof name, "slice_%04u.png", z);
    write_image(set.member(name), image);
  }
  set.commit();
}

void write_stats(const std::string& path, const std::string& mesh, const std::string& axis, const Voxelization& v,
                 const std::optional<VoxelCheck>& ref) {
  const VoxelStats& s = v.stats;
  JsonWriter json;
  json.begin_object().field("mesh", mesh).field("grid", v.grid.n).field("axis", axis);
  json.field("voxels", v.grid.count());
  write_counters(json, s.counters);
  json.field("merged", s.merged).field("odd_columns", s.odd_columns).field("attempts", s.attempts);
  json.field("table_slots", s.table_slots).field("load_factor", s.load_factor);
  json.field("memory_bytes", s.list_bytes).field("dense_bytes", v.grid.memory_bytes());
  json.field("gather_ms", s.gather_ms).field("parity_ms", s.parity_ms);
  if (ref) {
    const double voxels = static_cast<double>(v.grid.n) * v.grid.n * v.grid.n;
    json.key("reference").begin_object().field("mismatches", ref->mismatches).field("band", ref->band);
    json.field("band_fraction", static_cast<double>(ref->band) / voxels).end_object();
  }
  json.end_object();
  json.save(path);
}

// A mesh with holes is warned about even when no column happens to cross
// one an odd number of times: its inside is then a guess of the views.
void warn_open_meshes(const Scene& scene, std::uint64_t odd_columns) {
  if (odd_columns > 0) return;  // the odd columns' warning says it
  for (const Mesh& m : scene.meshes)
    if (const std::string why = solid_problem(check_solid(m)); !why.empty())
      std::fprintf(stderr, "habuffer voxelize: warning: mesh %s %s: it is not watertight, its inside is a guess\n",
                   excerpt(m.name).c_str(), why.c_str());
}

}  // namespace

int run_voxelize(const std::vector<std::string>& argv) {
  if (print_help(argv, voxelize_spec())) return 0;
  const Args args(argv, voxelize_spec());
  VoxelizeSettings s;
  s.grid = args.u32_in("grid", 1, 4096);
  const std::string axis = args.str("axis");
  if (axis != "x" && axis != "y" && axis != "z" && axis != "all")
    throw UsageError("option --axis: '" + axis + "' is not x, y, z or all");
  s.axis = axis == "x" ? VoxelAxis::X : axis == "y" ? VoxelAxis::Y : VoxelAxis::Z;
  const std::string path = args.str("path");
  if (path != "gl" && path != "cpu") throw UsageError("option --path: '" + path + "' is not gl or cpu");
  s.cpu = path == "cpu";
  s.threads = args.u32_in("threads", 0, 1024);
  args.refuse_unless(s.cpu, {"threads"}, "with --path gl (the GPU builds the lists)");
  const std::string mesh = args.required("mesh");
  if (args.has("vdb") && !has_vdb_support())
    throw UsageError("option --vdb: this habuffer was built without OpenVDB (" + vdb_support() + ")");
  if (args.has("slices") && !has_image_support())
    throw UsageError("option --slices: this habuffer was built without image files (" + image_support() + ")");
  const Scene scene = harness::voxel_mesh(mesh);
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("voxelize: no usable OpenGL: ") + e.what());
  }
  const Voxelization v = axis == "all" ? voxelize_voting(scene, s) : voxelize(scene, s);
  save_voxel_grid(args.required("out"), v.grid);
  if (args.has("nrrd")) save_voxel_nrrd(args.required("nrrd"), v.grid, "habuffer voxelize --mesh " + mesh);
  if (args.has("vdb")) save_voxel_vdb(args.required("vdb"), v.grid, "habuffer voxelize --mesh " + mesh);
  if (args.has("slices")) write_slices(args.required("slices"), v.grid);
  std::optional<VoxelCheck> ref;
  if (args.has("reference")) ref = axis == "all" ? check_voxels_voting(scene, s, v.grid) : check_voxels(scene, s, v.grid);
  if (args.has("stats")) write_stats(args.required("stats"), mesh, axis, v, ref);
  warn_open_meshes(scene, v.stats.odd_columns);
  if (v.stats.odd_columns > 0)
    std::fprintf(stderr, "habuffer voxelize: warning: %llu columns cross the surface an odd number of times: the mesh "
                         "is not watertight%s\n",
                 static_cast<unsigned long long>(v.stats.odd_columns), axis == "all" ? "" : "; try --axis all");
  if (v.stats.merged > 0)
    std::fprintf(stderr, "habuffer voxelize: warning: %llu crossings merged with an equal one (same facing, same "
                         "depth code): coincident faces, the parity behind them flips\n",
                 static_cast<unsigned long long>(v.stats.merged));
  if (!args.has("quiet")) {
    std::printf("%s %u^3 along %s: %llu voxels solid of %llu, %llu crossings (%llu merged, %llu odd columns), lists "
                "%.1f MiB against %.1f MiB of dense bits, gather %.1f ms, parity %.1f ms\n",
                mesh.c_str(), s.grid, axis.c_str(), static_cast<unsigned long long>(v.grid.count()),
                static_cast<unsigned long long>(std::uint64_t{s.grid} * s.grid * s.grid),
                static_cast<unsigned long long>(v.stats.counters.fragments),
                static_cast<unsigned long long>(v.stats.merged), static_cast<unsigned long long>(v.stats.odd_columns),
                static_cast<double>(v.stats.list_bytes) / (1 << 20),
                static_cast<double>(v.grid.memory_bytes()) / (1 << 20), v.stats.gather_ms, v.stats.parity_ms);
    if (ref)
      std::printf("reference: %llu mismatches outside a near-surface band of %llu voxels\n",
                  static_cast<unsigned long long>(ref->mismatches), static_cast<unsigned long long>(ref->band));
  }
  return 0;
}

}  // namespace habuffer::cli
