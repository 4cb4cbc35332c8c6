// Mesh files through assimp: every mesh of the file, node transforms
// applied, triangulated; each mesh keeps its material's diffuse colour.
#pragma once

#include <string>

#include "habuffer/scene.h"

namespace habuffer {

// Throws SceneError naming the file and what assimp reported.
Scene load_mesh_file(const std::string& path, float opacity);

}  // namespace habuffer
