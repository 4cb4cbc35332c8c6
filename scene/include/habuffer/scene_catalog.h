// The scenes `habuffer render --scene` knows: meshes of Debian's
// assimp-testmodels by name (engine, wuson, spider), procedural stress scenes
// after the papers (hairball, quads, planes), or any mesh file assimp reads.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "habuffer/scene.h"

namespace habuffer {

enum class PlaneOrder { FrontToBack, BackToFront };

struct SceneOptions {
  float opacity = 0.5f;      // of every mesh (1: opaque)
  std::uint64_t seed = 1;    // procedural scenes
  std::uint32_t count = 0;   // tubes, quads or planes; 0: the scene's default
  float spread = 1.0f;       // quads: 1 anywhere, 0 stacked exactly
  PlaneOrder order = PlaneOrder::BackToFront;
  // Opacity-1 meshes go through the buffer instead of the opaque pass.
  bool insert_opaque = false;
};

// Where the named meshes live: $HABUFFER_ASSIMP_MODELS, else
// /usr/share/assimp/models (Debian's assimp-testmodels).
std::string assimp_models_root();
std::vector<std::string> scene_names();
// Whether `name` is one of scene_names() (not a mesh file).
bool is_scene_name(const std::string& name);
// The procedural scenes that use SceneOptions' `option` ("count", "seed",
// "spread" or "order"); make_scene ignores it for every other scene.
std::vector<std::string> scenes_taking(const std::string& option);

// A scene name or a mesh file path. Throws SceneError naming what was wrong.
Scene make_scene(const std::string& name_or_path, const SceneOptions& options);

}  // namespace habuffer
