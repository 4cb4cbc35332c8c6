#include "habuffer/mesh_loader.h"

#include <cmath>
#include <fstream>

#include <glm/common.hpp>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "ply_check.h"

namespace habuffer {
namespace {

// Distinct colours for meshes whose material has none.
glm::vec3 palette(std::size_t i) {
  static const glm::vec3 colours[] = {{0.90f, 0.30f, 0.25f}, {0.25f, 0.55f, 0.90f}, {0.30f, 0.75f, 0.35f},
                                      {0.95f, 0.75f, 0.20f}, {0.65f, 0.40f, 0.85f}, {0.20f, 0.80f, 0.80f},
                                      {0.95f, 0.55f, 0.15f}, {0.75f, 0.75f, 0.75f}};
  return colours[i % std::size(colours)];
}

glm::vec3 diffuse_colour(const aiScene& s, const aiMesh& m, std::size_t index) {
  aiColor4D c;
  if (m.mMaterialIndex < s.mNumMaterials &&
      aiGetMaterialColor(s.mMaterials[m.mMaterialIndex], AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS) {
    const glm::vec3 v(c.r, c.g, c.b);
    // Materials with no colour of their own come back black or white: use the palette.
    if (v != glm::vec3(0.0f) && v != glm::vec3(1.0f) && std::isfinite(v.x + v.y + v.z))
      return glm::clamp(v, 0.0f, 1.0f);
  }
  return palette(index);
}

Mesh convert(const aiScene& s, const aiMesh& m, std::size_t index, float opacity) {
  Mesh out;
  out.name = m.mName.length > 0 ? m.mName.C_Str() : "mesh " + std::to_string(index);
  out.colour = diffuse_colour(s, m, index);
  out.opacity = opacity;
  out.positions.reserve(m.mNumVertices);
  for (unsigned v = 0; v < m.mNumVertices; ++v) out.positions.emplace_back(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines left by triangulation
    for (unsigned k = 0; k < 3; ++k)
      if (face.mIndices[k] >= m.mNumVertices)
        throw SceneError("mesh '" + out.name + "': face " + std::to_string(f) + " uses vertex " +
                         std::to_string(face.mIndices[k]) + " of " + std::to_string(m.mNumVertices));
    out.indices.insert(out.indices.end(), face.mIndices, face.mIndices + 3);
  }
  return out;
}

}  // namespace

Scene load_mesh_file(const std::string& path, float opacity) {
  if (!std::ifstream(path).good()) throw SceneError("mesh file '" + path + "' cannot be opened");
  if (is_ply_file(path)) check_ply_file(path);  // assimp trusts a PLY header: it may abort or allocate gigabytes
  Assimp::Importer importer;
  const aiScene* s = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                 aiProcess_PreTransformVertices | aiProcess_SortByPType |
                                                 aiProcess_ValidateDataStructure);
  if (s == nullptr || s->mRootNode == nullptr || (s->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
    throw SceneError("mesh file '" + path + "': " + importer.GetErrorString());
  Scene scene;
  scene.name = path;
  for (unsigned i = 0; i < s->mNumMeshes; ++i) {
    Mesh m = convert(*s, *s->mMeshes[i], i, opacity);
    if (!m.indices.empty()) scene.meshes.push_back(std::move(m));
  }
  if (scene.meshes.empty()) throw SceneError("mesh file '" + path + "' has no triangles");
  for (const Mesh& m : scene.meshes)
    for (const glm::vec3& p : m.positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw SceneError("mesh file '" + path + "': mesh '" + m.name + "' has a non-finite vertex");
  return scene;
}

}  // namespace habuffer
