/// @file
/// Mesh files through assimp: every mesh of the file, node transforms
/// applied, triangulated; each mesh keeps its material's diffuse colour.
#pragma once

#include <string>

#include "habuffer/scene.h"

namespace habuffer {

/// Every mesh of `path` at `opacity`. Throws SceneError naming the file and what assimp reported (a PLY
/// file's header is checked first: check_ply_file).
Scene load_mesh_file(const std::string& path, float opacity);

}  // namespace habuffer
