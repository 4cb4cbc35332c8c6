#include "habuffer/scene_catalog.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "habuffer/mesh_loader.h"
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

std::vector<std::string> scenes_taking(const std::string& option) {
  // As make_scene below passes them on.
  static const std::map<std::string, std::vector<std::string>> takers{
      {"count", {"hairball", "quads", "planes"}}, {"seed", {"hairball", "quads"}}, {"spread", {"quads"}},
      {"order", {"planes"}}};
  const auto it = takers.find(option);
  return it == takers.end() ? std::vector<std::string>{} : it->second;
}

bool is_scene_name(const std::string& name) {
  const std::vector<std::string> names = scene_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

namespace {

Scene make_scene_meshes(const std::string& name_or_path, const SceneOptions& o) {
  if (!(o.opacity > 0.0f && o.opacity <= 1.0f))
    throw SceneError("--opacity " + std::to_string(o.opacity) + " is not in (0, 1]");
  if (!(o.spread >= 0.0f && o.spread <= 1.0f)) throw SceneError("--spread " + std::to_string(o.spread) + " is not in [0, 1]");
  if (const auto it = named_meshes().find(name_or_path); it != named_meshes().end()) {
    const std::string path = assimp_models_root() + "/" + it->second;
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
