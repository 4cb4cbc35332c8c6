// habuffer csg: a CSG expression over named solids, rendered from lossless
// sorted lists (habuffer/render/csg_renderer.h), with its stats and the ray
// caster's comparison. (A command of its own rather than `render --csg`:
// render's options choose and size OIT techniques, none of which apply.)
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "commands.h"
#include "file_values.h"
#include <glm/geometric.hpp>

#include "habuffer/csv.h"
#include "habuffer/file_roles.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/json_writer.h"
#include "habuffer/list_text.h"
#include "habuffer/mesh_loader.h"
#include "habuffer/number_text.h"
#include "habuffer/printable.h"
#include "habuffer/solid_check.h"
#include "habuffer/render/csg_renderer.h"
#include "habuffer/render/image.h"
#include "habuffer/solids.h"
#include "report_json.h"

namespace habuffer::cli {
const CommandSpec& csg_spec() {
  static const CommandSpec spec{
      "csg --solids 'NAME=SPEC; ...' --expr EXPR (--out IMAGE | --stats S.json) [OPTIONS]",
      {{"solids", "NAME=SPEC;...", "",
        "the primitives, ';'-separated: box:x0,y0,z0,x1,y1,z1  sphere:cx,cy,cz,r  "
        "cylinder:bx,by,bz,ax,ay,az,length,radius  torus:cx,cy,cz,R,r  or a closed mesh file", reads_in(solid_files, "A={}")},
       {"expr", "EXPR", "", "names with | (union) & (intersection) - (difference) and parentheses"},
       {"out", "IMAGE", "", "the shaded image", writes_creating_parents()},
       {"stats", "S.json", "", "records, memory, times, and with --reference the mismatches", writes()},
       {"size", "WxH", "256x256", "the image"},
       {"yaw", "DEG", "30", "camera yaw"},
       {"pitch", "DEG", "25", "camera pitch in [-90, 90]"},
       {"fov", "DEG", "45", "vertical field of view in (1, 179)"},
       {"path", "gl|cpu", "gl", "where the lists are built (the same pixels)"},
       {"reference", "", "", "compare the visible primitive per pixel with the ray caster outside its edge band"},
       {"quiet", "", "", "no summary"}},
      "  Exit codes: 0 ok, 1 bad data (a mesh file, GL limits), 2 bad usage (a solid or the expression).\n"};
  return spec;
}

namespace {

std::vector<float> numbers(const std::string& solid, const std::string& text, std::size_t count) {
  std::vector<float> v;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      v.push_back(parse_float32(item));
    } catch (const std::invalid_argument& e) {
      throw UsageError("option --solids: " + solid + ": " + e.what());
    }
  }
  if (v.size() != count)
    throw UsageError("option --solids: " + solid + " takes " + std::to_string(count) + " numbers, not " +
                     std::to_string(v.size()));
  return v;
}

Mesh solid(const std::string& name, const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon), args = colon == std::string::npos ? "" : spec.substr(colon + 1);
  const std::string what = name + "=" + kind;
  try {
    if (kind == "box") {
      const auto n = numbers(what, args, 6);
      return box_mesh({n[0], n[1], n[2]}, {n[3], n[4], n[5]}, name);
    }
    if (kind == "sphere") {
      const auto n = numbers(what, args, 4);
      return sphere_mesh({n[0], n[1], n[2]}, n[3], 48, 24, name);
    }
    if (kind == "cylinder") {
      const auto n = numbers(what, args, 8);
      return cylinder_mesh({n[0], n[1], n[2]}, {n[3], n[4], n[5]}, n[6], n[7], 32, name);
    }
    if (kind == "torus") {
      const auto n = numbers(what, args, 5);
      return torus_mesh({n[0], n[1], n[2]}, n[3], n[4], 48, 24, name);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("option --solids: ") + e.what());
  }
  // A mesh file: every mesh in it one primitive.
  const Scene file = load_mesh_file(spec, 1.0f);
  Mesh m;
  m.name = name;
  for (const Mesh& part : file.meshes) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), part.positions.begin(), part.positions.end());
    for (const std::uint32_t i : part.indices) m.indices.push_back(base + i);
  }
  return m;
}

// A name --expr can refer to: operators and spaces separate names there.
void check_solid_name(const std::string& name) {
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
  if (std::isdigit(static_cast<unsigned char>(name[0])) != 0 || !std::all_of(name.begin(), name.end(), word))
    throw UsageError("option --solids: solid name " + excerpt(name) +
                     " must be letters, digits and '_', not starting with a digit (--expr reads - | & ( ) and spaces "
                     "as operators)");
}

// Each solid must bound a volume the renderer can resolve: closed,
// manifold, non-zero volume (solid_check.h), and at least 2^-20 of the
// scene's size: float32 positions and depths keep about 2^-20 of the
// scene's extent (camera.h's depth-range rule), so a smaller solid has no
// depth of its own. Solids smaller than a pixel are warned about.
void check_solids(const Scene& scene, Extent screen) {
  const Bounds all = scene.bounds();
  const float scene_size = glm::length(all.hi - all.lo);
  for (const Mesh& m : scene.meshes) {
    if (const std::string why = solid_problem(check_solid(m)); !why.empty())
      throw DataError("option --solids: solid " + excerpt(m.name) + " " + why + " (csg needs closed solids)");
    Bounds b;
    for (const glm::vec3& p : m.positions) b.add(p);
    const float size = glm::length(b.hi - b.lo);
    if (!(size >= scene_size * 0x1.0p-20f))
      throw UsageError("option --solids: solid " + excerpt(m.name) + " is " + shortest(size) + " across in a scene " +
                       shortest(scene_size) + " across: below 2^-20 of it, float32 depths cannot resolve it");
    if (size * static_cast<float>(std::min(screen.x, screen.y)) < scene_size)
      std::fprintf(stderr, "habuffer csg: warning: solid %s (%g across in a scene %g across) covers less than a pixel "
                           "at --size %s\n",
                   excerpt(m.name).c_str(), static_cast<double>(size), static_cast<double>(scene_size),
                   screen.str().c_str());
  }
}

std::pair<Scene, std::vector<std::string>> parse_solids(const std::string& text) {
  Scene scene;
  scene.name = "csg";
  std::vector<std::string> names;
  for (std::string item : split_list(text, ';')) {  // the rule solid_files reads the files by
    const auto first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
    if (first == std::string::npos) continue;
    item = item.substr(first, last - first + 1);
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw UsageError("option --solids: '" + item + "' is not NAME=SPEC");
    const std::string name = item.substr(0, eq);
    check_solid_name(name);
    for (const std::string& n : names)
      if (n == name) throw UsageError("option --solids: '" + name + "' is named twice");
    scene.meshes.push_back(solid(name, item.substr(eq + 1)));
    names.push_back(name);
  }
  if (names.empty()) throw UsageError("option --solids: no solid given");
  return {std::move(scene), std::move(names)};
}

void write_csg_stats(const std::string& file, const CsgExpression& expression, Extent screen, const std::string& path,
                     std::uint64_t covered, const CsgRender& r, const std::optional<CsgCheck>& check) {
  JsonWriter json;
  json.begin_object().field("expression", expression.text()).field("primitives", expression.primitives());
  write_extent(json, "size", screen);
  json.field("path", path).field("covered_pixels", covered);
  write_counters(json, r.counters);
  json.field("attempts", r.attempts).field("memory_bytes", r.list_bytes);
  json.field("gather_ms", r.gather_ms).field("resolve_ms", r.resolve_ms);
  if (check) json.key("reference").begin_object().field("mismatches", check->mismatches).field("band", check->band).end_object();
  json.end_object();
  json.save(file);
}

}  // namespace

int run_csg(const std::vector<std::string>& argv) {
  if (print_help(argv, csg_spec())) return 0;
  const Args args(argv, csg_spec());
  if (!args.has("out") && !args.has("stats")) throw UsageError("give --out IMAGE (and/or --stats S.json)");
  CsgRenderSettings s;
  s.screen = args.size("size");
  s.camera.yaw = static_cast<float>(args.real("yaw"));
  s.camera.pitch = static_cast<float>(args.real("pitch"));
  s.camera.fov = static_cast<float>(args.real("fov"));
  const std::string path = args.str("path");
  if (path != "gl" && path != "cpu") throw UsageError("option --path: '" + path + "' is not gl or cpu");
  s.cpu = path == "cpu";
  if (args.has("out") && !has_image_support())
    throw UsageError("option --out: this habuffer was built without image files (" + image_support() + ")");
  if (args.has("out")) usage_errors("out", [&] { check_image_extension(args.required("out")); });
  auto [scene, names] = parse_solids(args.required("solids"));
  check_solids(scene, s.screen);
  std::optional<CsgExpression> expression;
  try {
    expression = CsgExpression::parse(args.required("expr"), names);
  } catch (const CsgError& e) {
    throw UsageError(std::string("option --expr: ") + e.what());
  }
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("csg: no usable OpenGL: ") + e.what());
  }
  const CsgRender r = render_csg(scene, *expression, s);
  std::optional<CsgCheck> check;
  if (args.has("reference")) check = check_csg(scene, *expression, r, s.screen);
  if (args.has("out")) write_image(args.required("out"), r.image);
  std::uint64_t covered = 0;
  for (const std::int32_t id : r.primitive) covered += id >= 0;
  if (args.has("stats")) write_csg_stats(args.required("stats"), *expression, s.screen, path, covered, r, check);
  if (!args.has("quiet")) {
    std::printf("csg %s over %u primitives, %s: %llu pixels covered, %llu records, %.1f MiB, gather %.1f ms, resolve "
                "%.1f ms\n",
                expression->text().c_str(), expression->primitives(), s.screen.str().c_str(),
                static_cast<unsigned long long>(covered), static_cast<unsigned long long>(r.counters.stored()),
                static_cast<double>(r.list_bytes) / (1 << 20), r.gather_ms, r.resolve_ms);
    if (check)
      std::printf("reference: %llu pixels differ outside an edge band of %llu\n",
                  static_cast<unsigned long long>(check->mismatches), static_cast<unsigned long long>(check->band));
  }
  return 0;
}

}  // namespace habuffer::cli
