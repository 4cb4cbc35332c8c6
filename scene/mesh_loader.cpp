#include "habuffer/mesh_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "habuffer/file_roles.h"
#include "habuffer/polygon_triangulation.h"
#include "habuffer/solid_check.h"
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

// Vertices at exactly the same position become one (bit patterns compared,
// -0 as +0): the importer gives each face corner its own vertex.
void weld_identical(Mesh& m) {
  const std::vector<std::uint32_t> to = exact_vertex_ids(m.positions);
  std::vector<glm::vec3> kept;
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (to[i] == kept.size()) kept.push_back(m.positions[i]);  // ids are numbered by first appearance
  for (std::uint32_t& index : m.indices) index = to[index];
  m.positions = std::move(kept);
}

// The welded triangles must enclose the volume of the file's polygons over
// the file's own vertices (`file_volume`; up to rounding, relative to the
// sum of the volume's terms' magnitudes, and to the bend of polygons that are
// not planar): a check of the triangulation and the weld that shares
// neither's code.
void check_triangulation(const Mesh& m, double magnitude) {
  const double triangles = triangles_volume(m.positions, m.indices);
  if (std::abs(triangles - m.file_volume) > 1e-6 * magnitude + 1e-300)
    throw SceneError("mesh '" + m.name + "': its triangles enclose a volume of " + std::to_string(triangles) +
                     ", its polygons " + std::to_string(m.file_volume) + " (polygons that are not planar?)");
}

Mesh convert(const aiScene& s, const aiMesh& m, std::size_t index, float opacity) {
  Mesh out;
  out.name = m.mName.length > 0 ? m.mName.C_Str() : "mesh " + std::to_string(index);
  out.colour = diffuse_colour(s, m, index);
  out.opacity = opacity;
  out.positions.reserve(m.mNumVertices);
  for (unsigned v = 0; v < m.mNumVertices; ++v) out.positions.emplace_back(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
  // Polygons are triangulated here, not by assimp: its triangulation
  // compares areas with fixed epsilons and breaks closed meshes at small
  // scales (a cube of quads at 1e-6). The file's own polygons give the
  // volume the triangles must enclose: a check that shares nothing with the
  // triangulation (polygon_triangulation.h).
  std::vector<std::vector<std::uint32_t>> polygons;
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices < 3) continue;  // points and lines
    for (unsigned k = 0; k < face.mNumIndices; ++k)
      if (face.mIndices[k] >= m.mNumVertices)
        throw SceneError("mesh '" + out.name + "': face " + std::to_string(f) + " uses vertex " +
                         std::to_string(face.mIndices[k]) + " of " + std::to_string(m.mNumVertices));
    polygons.emplace_back(face.mIndices, face.mIndices + face.mNumIndices);
    triangulate_polygon(out.positions, polygons.back(), out.indices);
  }
  double magnitude = 0.0;
  out.file_volume = polygons_volume(out.positions, polygons, &magnitude);
  weld_identical(out);
  check_triangulation(out, magnitude);
  return out;
}

}  // namespace

Scene load_mesh_file(const std::string& path, float opacity) {
  try {
    check_input_file(path, "mesh file");
  } catch (const std::exception& e) {
    throw SceneError(std::string("mesh file: ") + e.what());
  }
  if (std::error_code ec; !std::filesystem::is_regular_file(path, ec))
    throw SceneError("mesh file '" + path + "' is a pipe: meshes are read by assimp, which needs a regular file");
  if (!std::ifstream(path).good()) throw SceneError("mesh file '" + path + "' cannot be opened");
  if (is_ply_file(path)) check_ply_file(path);  // assimp trusts a PLY header: it may abort or allocate gigabytes
  Assimp::Importer importer;
  // No aiProcess_Triangulate (see convert) and so no aiProcess_SortByPType:
  // a mesh of triangles and quads stays one mesh. No
  // aiProcess_JoinIdenticalVertices either: it merges vertices closer than
  // an epsilon, which at small scales (a cube of side 1e-6) joins distinct
  // corners; weld_identical joins exactly equal positions instead.
  const aiScene* s = importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure);
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
