// habuffer_csg_peers: habuffer's CSG from sorted depth lists beside OpenCSG's
// Goldfeather and SCS on the same EGL context (a compatibility profile, which
// OpenCSG needs), on the CSG curve (a cube minus 1..512 cylinders: one
// product of convex primitives) and on nested differences (several
// products). Each render is timed (median of repeats, to glFinish) and its
// visible primitive per pixel checked against the ray caster
// (csg_reference) outside the edge band. GPL-2+ through OpenCSG: a benchmark
// only, never part of the library or the CLI.
//
// usage: habuffer_csg_peers [--cylinders 1,2,...] [--size WxH] [--repeats N] [--out F.json[,F.csv]]
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "habuffer/csg.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/harness/csg_figure.h"
#include "habuffer/harness/result_table.h"
#include "habuffer/render/csg_renderer.h"
#include "habuffer/solids.h"
#include "opencsg_peer.h"

namespace {

using namespace habuffer;
using peers::CsgProduct;
using peers::OpenCsgAlgorithm;
using peers::OpenCsgMethod;

struct Options {
  std::vector<std::uint32_t> cylinders{1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
  Extent size{128, 128};
  std::uint32_t repeats = 3;
  std::vector<std::string> out;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "habuffer_csg_peers: %s\nusage: habuffer_csg_peers [--cylinders 1,2,...] [--size WxH] [--repeats N] "
               "[--out F.json[,F.csv]]\n",
               why.c_str());
  std::exit(2);
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::uint32_t count(const std::string& option, const std::string& text, std::uint32_t max) {
  std::size_t used = 0;
  unsigned long v = 0;
  try {
    v = std::stoul(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || v == 0 || v > max)
    usage("option " + option + ": '" + text + "' is not a count in 1.." + std::to_string(max));
  return static_cast<std::uint32_t>(v);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) usage("option " + a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--cylinders") {
      o.cylinders.clear();
      for (const std::string& c : split(v)) o.cylinders.push_back(count(a, c, 4095));
    } else if (a == "--size") {
      const std::optional<Extent> e = parse_extent(v);
      if (!e || e->x > 4096 || e->y > 4096) usage("option --size: '" + v + "' is not WxH with sides in 1..4096");
      o.size = *e;
    } else if (a == "--repeats") {
      o.repeats = count(a, v, 1000);
    } else if (a == "--out") {
      o.out = split(v);
    } else {
      usage("unknown option " + a);
    }
  }
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One workload: primitives, our expression, and the same as OpenCSG's products.
struct Workload {
  std::string name;
  Scene scene;
  std::vector<std::string> names;
  std::string expression;
  std::vector<CsgProduct> products;
};

Workload cylinders_workload(std::uint32_t n) {
  harness::CsgCylinders c = harness::csg_cylinders(n);
  Workload w{"cube - " + std::to_string(n) + " cylinders", std::move(c.scene), std::move(c.names), c.expression, {}};
  CsgProduct p{{0}, {}};
  for (std::uint32_t k = 1; k <= n; ++k) p.subtracted.push_back(k);
  w.products.push_back(p);
  return w;
}

// Nested differences: cube - (sphere - (cylinder - rod)), whose sum of
// products is cube-sphere, cube&sphere&cylinder-rod.
Workload nested_workload() {
  Workload w;
  w.name = "cube - (sphere - (cylinder - rod))";
  w.scene.name = w.name;
  w.scene.meshes = {box_mesh({-1, -1, -1}, {1, 1, 1}, "cube"), sphere_mesh({0, 0, 0}, 1.3f, 48, 24, "sphere"),
                    cylinder_mesh({0, 0, -1.6f}, {0, 0, 1}, 3.2f, 0.6f, 32, "cylinder"),
                    cylinder_mesh({0, -1.6f, 0}, {0, 1, 0}, 3.2f, 0.25f, 32, "rod")};
  w.names = {"cube", "sphere", "cylinder", "rod"};
  w.expression = "cube - (sphere - (cylinder - rod))";
  w.products = {CsgProduct{{0}, {1}}, CsgProduct{{0, 1, 2}, {3}}};
  return w;
}

void run(const Workload& w, std::uint32_t cylinders, const Options& o, harness::ResultTable& table) {
  const CsgExpression e = CsgExpression::parse(w.expression, w.names);
  CsgRenderSettings s;
  s.screen = o.size;
  s.camera = {30.0f, 25.0f, 45.0f};
  std::vector<double> ours;
  CsgRender r;
  for (std::uint32_t k = 0; k < o.repeats; ++k) {
    r = render_csg(w.scene, e, s);
    ours.push_back(r.gather_ms + r.resolve_ms);
  }
  const auto row = [&](const std::string& method, const std::vector<double>& ms, const CsgCheck& check) {
    harness::ResultRow x;
    x.set("workload", w.name).set("cylinders", cylinders).set("method", method).set("ms", median(ms))
        .set("ms_min", *std::min_element(ms.begin(), ms.end())).set("mismatches", check.mismatches)
        .set("band", check.band).set("pixels", o.size.area());
    table.rows.push_back(x);
    std::printf("%-36s %-20s %9.2f ms  %6llu mismatches (band %llu)\n", w.name.c_str(), method.c_str(), median(ms),
                static_cast<unsigned long long>(check.mismatches), static_cast<unsigned long long>(check.band));
    std::fflush(stdout);
  };
  row("habuffer-ha", ours, check_csg(w.scene, e, r, o.size));
  // Every primitive is convex: convexity 1 (what SCS assumes and Goldfeather reads).
  peers::OpenCsgPeer peer(w.scene, std::vector<std::uint32_t>(w.scene.meshes.size(), 1), o.size);
  const peers::OpenCsgMethod methods[] = {{OpenCsgAlgorithm::Goldfeather, true},
                                         {OpenCsgAlgorithm::Goldfeather, false},
                                         {OpenCsgAlgorithm::Scs, true}};
  for (const peers::OpenCsgMethod& a : methods) {
    std::vector<double> ms;
    peers::OpenCsgRender p;
    for (std::uint32_t k = 0; k < o.repeats + 1; ++k) {  // one more: the first compiles OpenCSG's programs
      p = peer.render(w.products, r.camera, a);
      if (k > 0) ms.push_back(p.ms);
    }
    CsgRender as_ours;
    as_ours.primitive = std::move(p.primitive);
    as_ours.camera = r.camera;
    row("opencsg-" + a.name(), ms, check_csg(w.scene, e, as_ours, o.size));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    if (!o.out.empty()) harness::check_table_paths(o.out);
    peers::CompatContext context;
    harness::ResultTable table;
    table.title = "csg peers";
    std::string command = "habuffer_csg_peers";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    table.provenance.command = command;
    table.provenance.machine = harness::machine_description();
    table.provenance.renderer = gl::query_gl_info().renderer + " (" + gl::query_gl_info().version + ")";
    for (std::uint32_t n : o.cylinders) run(cylinders_workload(n), n, o, table);
    run(nested_workload(), 0, o, table);
    table.notes["workload"] = "a cube minus N cylinders on a grid through it (one product of convex primitives), and "
                              "cube - (sphere - (cylinder - rod)) (two products), " + o.size.str() + ", yaw 30 pitch 25";
    table.notes["ms"] = "one render to glFinish, median of " + std::to_string(o.repeats) +
                        ": habuffer's lossless gather and per-pixel walk; OpenCSG's render and the shading pass";
    table.notes["mismatches"] = "pixels whose visible primitive differs from the ray caster's outside its edge band";
    table.notes["context"] = "one EGL context, OpenGL 4.5 compatibility profile (OpenCSG's fixed function), convexity 1";
    if (!o.out.empty()) harness::write_table(table, o.out);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "habuffer_csg_peers: %s\n", e.what());
    return 1;
  }
}
