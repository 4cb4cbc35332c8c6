#include "habuffer/solid_check.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include <glm/common.hpp>

#include "habuffer/polygon_triangulation.h"

namespace habuffer {
namespace {

struct PointKey {
  std::uint32_t x, y, z;
  bool operator==(const PointKey&) const = default;
};
struct PointHash {
  std::size_t operator()(const PointKey& k) const {
    return (std::size_t{k.x} * 0x9E3779B97F4A7C15ULL) ^ (std::size_t{k.y} * 0xC2B2AE3D27D4EB4FULL) ^ k.z;
  }
};

PointKey key_of(glm::vec3 p) {
  PointKey k{};
  p += glm::vec3(0.0f);  // -0 and +0 are one point
  std::memcpy(&k.x, &p.x, 4);
  std::memcpy(&k.y, &p.y, 4);
  std::memcpy(&k.z, &p.z, 4);
  return k;
}

}  // namespace

std::vector<std::uint32_t> exact_vertex_ids(std::span<const glm::vec3> positions) {
  std::unordered_map<PointKey, std::uint32_t, PointHash> ids;
  std::vector<std::uint32_t> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    out[i] = ids.emplace(key_of(positions[i]), static_cast<std::uint32_t>(ids.size())).first->second;
  return out;
}

SolidCheck check_solid(const Mesh& mesh) {
  SolidCheck c;
  const std::vector<std::uint32_t> welded = exact_vertex_ids(mesh.positions);
  // Per undirected edge: the triangles running it low-to-high and high-to-low.
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t v[3] = {welded[mesh.indices[t]], welded[mesh.indices[t + 1]], welded[mesh.indices[t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      ++c.degenerate;
      continue;
    }
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = v[e], b = v[(e + 1) % 3];
      auto& count = edges[(std::uint64_t{std::min(a, b)} << 32) | std::max(a, b)];
      (a < b ? count.first : count.second) += 1;
    }
  }
  for (const auto& [edge, count] : edges) {
    if (count.first + count.second == 1) ++c.boundary_edges;
    else if (count.first != 1 || count.second != 1) ++c.non_manifold_edges;
  }
  c.volume = triangles_volume(mesh.positions, mesh.indices);
  if (c.degenerate > 0 && !mesh.positions.empty()) {
    Bounds box;
    for (const glm::vec3& p : mesh.positions) box.add(p);
    const glm::dvec3 extent = glm::dvec3(box.hi) - glm::dvec3(box.lo);
    const glm::dvec3 largest = glm::max(glm::abs(glm::dvec3(box.lo)), glm::abs(glm::dvec3(box.hi)));
    c.float32_limited = std::max({extent.x, extent.y, extent.z}) <
                        std::ldexp(std::max({largest.x, largest.y, largest.z}), -16);
  }
  return c;
}

std::string solid_problem(const SolidCheck& check) {
  if (!check.closed() && check.degenerate > 0)
    return "has " + std::to_string(check.degenerate) + " triangles collapsed to a line or a point " +
           (check.float32_limited ? std::string("(float32 cannot hold its size at its position)")
                                  : std::string("(faces that repeat a corner: the file's own, two of its vertices at "
                                                "one point)"));
  if (check.boundary_edges > 0)
    return "is not closed: " + std::to_string(check.boundary_edges) + " edges belong to one triangle only (holes)";
  if (check.non_manifold_edges > 0)
    return "is not a manifold surface: " + std::to_string(check.non_manifold_edges) +
           " edges are shared by more than two triangles or by two facing the same way";
  if (!(std::abs(check.volume) > 0.0)) return "encloses no volume";
  return {};
}

}  // namespace habuffer
