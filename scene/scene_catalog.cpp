#include "habuffer/scene_catalog.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <map>
#include <stdexcept>

#include "habuffer/mesh_loader.h"
#include "habuffer/number_text.h"
#include "habuffer/procedural_scenes.h"

namespace habuffer {
namespace {

const std::map<std::string, std::string>& named_meshes() {
  static const std::map<std::string, std::string> m{
      {"engine", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"},
      {"wuson", "PLY/Wuson.ply"},
      {"spider", "OBJ/spider.obj"}};
  return m;
}

std::uint32_t or_default(std::uint32_t count, std::uint32_t fallback) { return count > 0 ? count : fallback; }

}  // namespace

std::string assimp_models_root() {
  const char* env = std::getenv("HABUFFER_ASSIMP_MODELS");
  return env != nullptr && *env != '\0' ? env : "/usr/share/assimp/models";
}

std::vector<std::string> scene_names() {
  std::vector<std::string> names;
  for (const auto& [name, file] : named_meshes()) names.push_back(name);
  for (const char* n : {"hairball", "quads", "planes"}) names.emplace_back(n);
  return names;
}

float smallest_opacity() { return std::nextafter(1.0f / 510.0f, 1.0f); }

namespace {

void set_count(SceneOptions& o, const std::string& text) {
  o.count = static_cast<std::uint32_t>(parse_unsigned(text, 1, kMaxSceneCount));
}
void set_seed(SceneOptions& o, const std::string& text) { o.seed = parse_unsigned(text); }
void set_opacity(SceneOptions& o, const std::string& text) {
  const float a = parse_float32(text);
  if (!(a >= smallest_opacity() && a <= 1.0f))
    throw std::invalid_argument(text + " outside (0, 1], at least " + shortest_text(smallest_opacity()) +
                                " (just above 1/510: smaller rounds to alpha 0 in the 8-bit record)");
  o.opacity = a;
}
void set_spread(SceneOptions& o, const std::string& text) {
  const float v = parse_float32(text);
  if (!(v >= 0.0f && v <= 1.0f)) throw std::invalid_argument(text + " outside [0, 1]");
  o.spread = v;
}
void set_order(SceneOptions& o, const std::string& text) {
  if (text != "front" && text != "back") throw std::invalid_argument("'" + text + "' is not front or back");
  o.order = text == "front" ? PlaneOrder::FrontToBack : PlaneOrder::BackToFront;
}

// The rule of `key`; throws std::invalid_argument naming the keys there are.
const SceneOptionRule& rule_of(const std::string& key) {
  std::string keys;
  for (const SceneOptionRule& r : scene_option_rules()) {
    if (key == r.key) return r;
    keys += (keys.empty() ? "" : ", ") + std::string(r.key);
  }
  throw std::invalid_argument("unknown scene option '" + key + "' (" + keys + ")");
}

}  // namespace

const std::vector<SceneOptionRule>& scene_option_rules() {
  // The takers as make_scene below passes the options on.
  static const std::vector<SceneOptionRule> rules{
      {"count", "count", {"hairball", "quads", "planes"}, set_count},
      {"seed", "scene-seed", {"hairball", "quads"}, set_seed},
      {"opacity", "opacity", {}, set_opacity},
      {"spread", "spread", {"quads"}, set_spread},
      {"order", "order", {"planes"}, set_order}};
  return rules;
}

std::vector<std::string> scenes_taking(const std::string& option) { return rule_of(option).takers; }

void set_scene_option(SceneOptions& o, const std::string& key, const std::string& text) { rule_of(key).set(o, text); }

bool scene_takes(const std::string& name_or_path, const std::string& key) {
  const std::vector<std::string>& takers = rule_of(key).takers;
  return takers.empty() || std::find(takers.begin(), takers.end(), name_or_path) != takers.end();
}

std::string scenes_taking_text(const std::string& key) {
  const std::vector<std::string>& takers = rule_of(key).takers;
  if (takers.empty()) return "every scene takes it";
  std::string names;
  for (const std::string& t : takers) names += (names.empty() ? "" : ", ") + t;
  return names + " take" + (takers.size() == 1 ? "s" : "") + " it";
}

bool is_scene_name(const std::string& name) {
  const std::vector<std::string> names = scene_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string scene_input_file(const std::string& name_or_path) {
  if (const auto it = named_meshes().find(name_or_path); it != named_meshes().end())
    return assimp_models_root() + "/" + it->second;
  return is_scene_name(name_or_path) ? std::string() : name_or_path;
}

namespace {

Scene make_scene_meshes(const std::string& name_or_path, const SceneOptions& o) {
  if (!(o.opacity >= smallest_opacity() && o.opacity <= 1.0f))
    throw SceneError("opacity " + shortest_text(o.opacity) + " is not in (0, 1] above 1/510");
  if (o.count > kMaxSceneCount)
    throw SceneError("count " + std::to_string(o.count) + " is above " + std::to_string(kMaxSceneCount));
  if (!(o.spread >= 0.0f && o.spread <= 1.0f)) throw SceneError("--spread " + std::to_string(o.spread) + " is not in [0, 1]");
  if (const auto it = named_meshes().find(name_or_path); it != named_meshes().end()) {
    const std::string path = scene_input_file(name_or_path);
    if (!std::filesystem::exists(path))
      throw SceneError("scene '" + name_or_path + "' needs " + path +
                       " (Debian package assimp-testmodels; ./scripts/setup.sh installs it)");
    Scene s = load_mesh_file(path, o.opacity);
    s.name = name_or_path;
    return s;
  }
  if (name_or_path == "hairball") return make_hairball(or_default(o.count, 1500), o.seed, o.opacity);
  if (name_or_path == "quads") return make_quads(or_default(o.count, 64), o.spread, o.seed, o.opacity);
  if (name_or_path == "planes") return make_planes(or_default(o.count, 16), o.order, o.opacity);
  if (std::filesystem::exists(name_or_path)) {
    if (!std::filesystem::is_regular_file(name_or_path))
      throw SceneError("mesh file '" + name_or_path + "' is not a regular file");
    return load_mesh_file(name_or_path, o.opacity);
  }
  if (name_or_path.find_first_of("/.") != std::string::npos)
    throw SceneError("mesh file '" + name_or_path + "' does not exist");
  std::string names;
  for (const std::string& n : scene_names()) names += (names.empty() ? "" : ", ") + n;
  throw SceneError("unknown scene '" + name_or_path + "': neither a scene name (" + names + ") nor an existing mesh file");
}

}  // namespace

Scene make_scene(const std::string& name_or_path, const SceneOptions& o) {
  Scene s = make_scene_meshes(name_or_path, o);
  for (Mesh& m : s.meshes) m.insert_opaque = o.insert_opaque;
  return s;
}

}  // namespace habuffer
