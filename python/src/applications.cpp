// The paper's applications from Python: solid voxelization of a mesh
// (habuffer voxelize) as a dense numpy grid, with the exact ray-parity
// reference on request. Runs on the module's GL context.
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "gl_context.h"
#include "habuffer/harness/voxel_figure.h"
#include "habuffer/render/voxelizer.h"

namespace habuffer::python {
namespace {

using namespace pybind11::literals;

// The grid as a (N, N, N) bool array indexed [z, y, x] (the grid's own order: x fastest).
py::array_t<bool> dense_grid(const VoxelGrid& g) {
  const py::ssize_t n = g.n;
  py::array_t<bool> out({n, n, n});
  bool* p = out.mutable_data();
  const std::uint64_t voxels = std::uint64_t{g.n} * g.n * g.n;
  for (std::uint64_t i = 0; i < voxels; ++i) p[i] = (g.words[i / 64] >> (i % 64)) & 1u;
  return out;
}

py::tuple voxelize_mesh(const std::string& mesh, const IntArg& grid, const std::string& axis, const std::string& path,
                        const IntArg& threads, bool reference) {
  VoxelizeSettings s;
  s.grid = u32_arg(grid, "grid", 1, 4096);  // as habuffer voxelize --grid
  if (axis != "x" && axis != "y" && axis != "z" && axis != "all")
    throw py::value_error("axis: '" + axis + "' is not x, y, z or all");
  s.axis = axis == "x" ? VoxelAxis::X : axis == "y" ? VoxelAxis::Y : VoxelAxis::Z;
  if (path != "gl" && path != "cpu") throw py::value_error("path: '" + path + "' is not gl or cpu");
  s.cpu = path == "cpu";
  s.threads = threads_arg(threads);
  s.validate();
  const Scene scene = harness::voxel_mesh(mesh);
  std::optional<Voxelization> v;
  std::optional<VoxelCheck> ref;
  {
    py::gil_scoped_release release;  // before the context's lock: never wait for it holding the GIL
    const GlContextUse use;
    v = axis == "all" ? voxelize_voting(scene, s) : voxelize(scene, s);
    if (reference) ref = axis == "all" ? check_voxels_voting(scene, s, v->grid) : check_voxels(scene, s, v->grid);
  }
  const VoxelStats& st = v->stats;
  py::dict stats("voxels"_a = v->grid.count(), "crossings"_a = st.counters.fragments, "merged"_a = st.merged,
                 "odd_columns"_a = st.odd_columns, "attempts"_a = st.attempts, "table_slots"_a = st.table_slots,
                 "load_factor"_a = st.load_factor, "memory_bytes"_a = st.list_bytes,
                 "dense_bytes"_a = v->grid.memory_bytes(), "gather_ms"_a = st.gather_ms, "parity_ms"_a = st.parity_ms,
                 "box"_a = py::make_tuple(py::make_tuple(v->grid.box.lo.x, v->grid.box.lo.y, v->grid.box.lo.z),
                                          py::make_tuple(v->grid.box.hi.x, v->grid.box.hi.y, v->grid.box.hi.z)));
  if (ref) stats["reference"] = py::dict("mismatches"_a = ref->mismatches, "band"_a = ref->band);
  return py::make_tuple(dense_grid(v->grid), stats);
}

}  // namespace

void bind_applications(py::module_& m) {
  m.def("voxelize", &voxelize_mesh, py::arg("mesh"), py::kw_only(), py::arg("grid") = 128, py::arg("axis") = "z",
        py::arg("path") = "gl", py::arg("threads") = 0, py::arg("reference") = false,
        "habuffer voxelize: the solid voxels of `mesh` (sphere, torus, box, a catalog scene or a mesh file) on an "
        "N^3 grid over its bounding box, by the parity of each column's sorted crossings (the HA-buffer's lists; "
        "axis='all': two of three axes' votes). Returns (solid, stats): solid is a (N, N, N) bool array indexed "
        "[z, y, x]; with reference=True, stats['reference'] counts mismatches against the exact ray-parity "
        "reference outside its edge band. Runs on the module's GL context (GlError where none can be made).");
}

}  // namespace habuffer::python
