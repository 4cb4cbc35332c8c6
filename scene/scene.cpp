#include "habuffer/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace habuffer {

void Bounds::add(glm::vec3 p) {
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}


Bounds Scene::bounds() const {
  Bounds b;
  for (const Mesh& m : meshes)
    for (const glm::vec3& p : m.positions) b.add(p);
  return b;
}

float Scene::radius_around(glm::vec3 centre) const {
  float r2 = 0.0f;
  for (const Mesh& m : meshes)
    for (const glm::vec3& p : m.positions) r2 = std::max(r2, glm::dot(p - centre, p - centre));
  return std::sqrt(r2);
}

std::uint64_t Scene::triangle_count() const {
  std::uint64_t n = 0;
  for (const Mesh& m : meshes) n += m.indices.size() / 3;
  return n;
}

}  // namespace habuffer
