/// @file
/// The scenes `habuffer render --scene` knows: meshes of Debian's
/// assimp-testmodels by name (engine, wuson, spider), procedural stress scenes
/// after the papers (hairball, quads, planes), or any mesh file assimp reads;
/// and their options, declared once for the CLI's flags and the harness's words.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "habuffer/scene.h"

namespace habuffer {

/// The planes scene's submission order (--order).
enum class PlaneOrder {
  FrontToBack,  ///< nearest plane drawn first ("front")
  BackToFront   ///< farthest plane drawn first ("back")
};

/// What make_scene takes besides the name (each option's rule: scene_option_rules).
struct SceneOptions {
  float opacity = 0.5f;      ///< of every mesh (1: opaque)
  std::uint64_t seed = 1;    ///< procedural scenes
  std::uint32_t count = 0;   ///< tubes, quads or planes; 0: the scene's default
  float spread = 1.0f;       ///< quads: 1 anywhere, 0 stacked exactly
  PlaneOrder order = PlaneOrder::BackToFront;  ///< planes: submission order
  /// Opacity-1 meshes go through the buffer instead of the opaque pass.
  bool insert_opaque = false;
};

/// Where the named meshes live: $HABUFFER_ASSIMP_MODELS, else
/// /usr/share/assimp/models (Debian's assimp-testmodels).
std::string assimp_models_root();
/// The named scenes: the assimp meshes, then hairball, quads, planes.
std::vector<std::string> scene_names();
/// Whether `name` is one of scene_names() (not a mesh file).
bool is_scene_name(const std::string& name);
/// The file scene `name_or_path` reads: a catalog mesh's model file under
/// assimp_models_root() (engine, wuson, spider), the path itself for a mesh
/// file, empty for a procedural scene. A command declares it as an input, so
/// that no output replaces a model a scene name resolved to.
std::string scene_input_file(const std::string& name_or_path);
/// The scene options, declared once for `habuffer render`'s flags and the
/// harness's scene words ("planes:count=32:order=front"): each option's key
/// in words, its flag, the scenes that use it (make_scene ignores it for
/// every other scene) and how its text becomes the value.
struct SceneOptionRule {
  const char* key;                   ///< "count", "seed", "opacity", "spread", "order"
  const char* flag;                  ///< "count", "scene-seed", "opacity", "spread", "order"
  std::vector<std::string> takers;   ///< empty: every scene, mesh files included
  /// Sets the option from `text`; throws std::invalid_argument with the reason.
  void (*set)(SceneOptions& options, const std::string& text);
};
/// Every option's rule, one per key (a static table).
const std::vector<SceneOptionRule>& scene_option_rules();
/// The scenes that use option `option` (empty for one every scene uses).
std::vector<std::string> scenes_taking(const std::string& option);
/// Largest count of tubes, quads or planes (2^20).
inline constexpr std::uint32_t kMaxSceneCount = 1u << 20;
/// Smallest opacity: records carry alpha as a byte, round(255 a); at 1/510
/// and below it may be 0 (255 a is then at most one half, and GLSL may round
/// halves down).
float smallest_opacity();
/// Sets option `key` of `options` from `text` by its rule. Throws
/// std::invalid_argument with the reason alone ("'0' outside 1..1048576"),
/// for the caller to prefix with the flag or the word.
void set_scene_option(SceneOptions& options, const std::string& key, const std::string& text);
/// Whether scene `name_or_path` uses option `key` (false: make_scene would
/// ignore it). Throws std::invalid_argument for an unknown key.
bool scene_takes(const std::string& name_or_path, const std::string& key);
/// "hairball, quads, planes take it" / "no scene takes it" for messages.
std::string scenes_taking_text(const std::string& key);

/// A scene name or a mesh file path. Throws SceneError naming what was wrong.
Scene make_scene(const std::string& name_or_path, const SceneOptions& options);

}  // namespace habuffer
