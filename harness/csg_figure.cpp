#include "habuffer/harness/csg_figure.h"

#include <cmath>
#include <stdexcept>

#include "habuffer/harness/workload.h"
#include "habuffer/render/csg_renderer.h"
#include "habuffer/solids.h"

namespace habuffer::harness {

CsgCylinders csg_cylinders(std::uint32_t n) {
  if (n == 0 || n >= kMaxCsgPrimitives)
    throw std::invalid_argument("the CSG curve takes 1 to " + std::to_string(kMaxCsgPrimitives - 1) + " cylinders");
  CsgCylinders c;
  c.scene.name = "cube minus cylinders";
  c.scene.meshes.push_back(box_mesh({-1, -1, -1}, {1, 1, 1}, "cube"));
  c.names.push_back("cube");
  c.expression = "cube - (";
  const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (std::uint32_t k = 0; k < n; ++k) {
    const float x = -0.9f + 1.8f * (static_cast<float>(k % side) + 0.5f) / static_cast<float>(side);
    const float y = -0.9f + 1.8f * (static_cast<float>(k / side) + 0.5f) / static_cast<float>(side);
    std::string name = "c";
    name += std::to_string(k);
    c.scene.meshes.push_back(cylinder_mesh({x, y, -1.5f}, {0, 0, 1}, 3.0f, 0.7f / static_cast<float>(side), 12, name));
    if (k > 0) c.expression += " | ";
    c.expression += name;
    c.names.push_back(name);
  }
  c.expression += ")";
  return c;
}

ResultTable run_csg_figure(const CsgFigureSettings& f) {
  if (f.cylinders.empty()) throw std::invalid_argument("the CSG curve needs a cylinder count");
  if (f.repeats == 0) throw std::invalid_argument("--repeats must be at least 1");
  ResultTable table;
  table.title = "csg";
  std::uint64_t done = 0;
  for (const std::uint32_t n : f.cylinders) {
    const CsgCylinders c = csg_cylinders(n);
    const CsgExpression e = CsgExpression::parse(c.expression, c.names);
    CsgRenderSettings s;
    s.screen = f.size;
    s.camera = {30.0f, 25.0f, 45.0f};
    s.cpu = f.cpu;
    std::vector<double> ms;
    CsgRender r;
    for (std::uint32_t rep = 0; rep < f.repeats; ++rep) {
      r = render_csg(c.scene, e, s);
      ms.push_back(r.gather_ms + r.resolve_ms);
    }
    const CsgCheck check = check_csg(c.scene, e, r, f.size);
    const std::uint64_t wrong = check.mismatches, in_band = check.band;
    const Spread t = spread_of(ms);
    ResultRow row;
    row.set("cylinders", n).set("primitives", n + 1).set("path", f.cpu ? "cpu" : "gl");
    row.set("ms", t.median).set("ms_min", t.min).set("ms_max", t.max).set("gather_ms", r.gather_ms)
        .set("resolve_ms", r.resolve_ms).set("records", r.counters.stored()).set("attempts", r.attempts)
        .set("memory_bytes", r.list_bytes).set("mismatches", wrong).set("band", in_band);
    table.rows.push_back(row);
    if (f.on_progress) f.on_progress(++done, f.cylinders.size());
  }
  table.notes["workload"] = "a cube minus N cylinders on a grid through it, " + f.size.str() + ", yaw 30 pitch 25";
  table.notes["ms"] = "one render: the lossless gather (grown until nothing is dropped) and the per-pixel walk; median";
  table.notes["mismatches"] = "pixels whose visible primitive differs from the ray caster's outside its edge band";
  return table;
}

}  // namespace habuffer::harness
