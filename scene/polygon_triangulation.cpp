#include "habuffer/polygon_triangulation.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace habuffer {
namespace {

using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;

// Twice the signed area of triangle (a, b, c): positive counter-clockwise.
double orient(dvec2 a, dvec2 b, dvec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

// Whether p lies inside or on counter-clockwise triangle (a, b, c).
bool inside(dvec2 p, dvec2 a, dvec2 b, dvec2 c) {
  return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

// The polygon in its own plane: the Newell normal's largest axis dropped, the
// winding made counter-clockwise (the triangles keep the original order).
std::vector<dvec2> projected(std::span<const glm::vec3> positions, std::span<const std::uint32_t> polygon) {
  dvec3 normal(0.0);
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const dvec3 a(positions[polygon[i]]), b(positions[polygon[(i + 1) % n]]);
    normal += dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const dvec3 m = glm::abs(normal);
  const int drop = m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  const double flip = normal[drop] < 0.0 ? -1.0 : 1.0;
  std::vector<dvec2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const dvec3 p(positions[polygon[i]]);
    out[i] = dvec2(p[u], flip * p[v]);
  }
  return out;
}

bool convex(const std::vector<dvec2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    if (orient(p[i], p[(i + 1) % n], p[(i + 2) % n]) < 0.0) return false;
  return true;
}

// Whether vertex `at` of the remaining ring is an ear: convex, and no other
// remaining vertex inside its triangle.
bool is_ear(const std::vector<dvec2>& p, const std::vector<std::size_t>& ring, std::size_t at) {
  const std::size_t n = ring.size();
  const dvec2 a = p[ring[(at + n - 1) % n]], b = p[ring[at]], c = p[ring[(at + 1) % n]];
  if (orient(a, b, c) <= 0.0) return false;
  for (std::size_t k = 0; k < n; ++k) {
    if (k == at || k == (at + 1) % n || k == (at + n - 1) % n) continue;
    const dvec2 q = p[ring[k]];
    if (q == a || q == b || q == c) continue;  // a repeated vertex (a polygon touching itself)
    if (inside(q, a, b, c)) return false;
  }
  return true;
}

}  // namespace

void triangulate_polygon(std::span<const glm::vec3> positions, std::span<const std::uint32_t> polygon,
                         std::vector<std::uint32_t>& out) {
  const std::size_t n = polygon.size();
  if (n < 3) return;
  const std::vector<dvec2> p = projected(positions, polygon);
  if (n == 3 || convex(p)) {
    for (std::size_t i = 1; i + 1 < n; ++i) out.insert(out.end(), {polygon[0], polygon[i], polygon[i + 1]});
    return;
  }
  std::vector<std::size_t> ring(n);
  for (std::size_t i = 0; i < n; ++i) ring[i] = i;
  while (ring.size() > 3) {
    std::size_t ear = ring.size();
    for (std::size_t k = 0; k < ring.size() && ear == ring.size(); ++k)
      if (is_ear(p, ring, (k + 1) % ring.size())) ear = (k + 1) % ring.size();
    // No ear (a self-intersecting or degenerate outline): cut the vertex
    // whose triangle turns most to the left, so n - 2 triangles still come out.
    if (ear == ring.size()) {
      double best = -INFINITY;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const std::size_t m = ring.size();
        const double turn = orient(p[ring[(k + m - 1) % m]], p[ring[k]], p[ring[(k + 1) % m]]);
        if (turn > best) best = turn, ear = k;
      }
    }
    const std::size_t m = ring.size();
    out.insert(out.end(), {polygon[ring[(ear + m - 1) % m]], polygon[ring[ear]], polygon[ring[(ear + 1) % m]]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  out.insert(out.end(), {polygon[ring[0]], polygon[ring[1]], polygon[ring[2]]});
}

double polygons_volume(std::span<const glm::vec3> positions, const std::vector<std::vector<std::uint32_t>>& polygons,
                       double* magnitude) {
  double six_v = 0.0, six_m = 0.0;
  for (const std::vector<std::uint32_t>& f : polygons) {
    if (f.size() < 3) continue;
    const dvec3 p0(positions[f[0]]);
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const double term = glm::dot(p0, glm::cross(dvec3(positions[f[i]]), dvec3(positions[f[i + 1]])));
      six_v += term;
      six_m += std::abs(term);
    }
  }
  if (magnitude != nullptr) *magnitude = six_m / 6.0;
  return six_v / 6.0;
}

double triangles_volume(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
  double six_v = 0.0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    six_v += glm::dot(dvec3(positions[indices[t]]),
                      glm::cross(dvec3(positions[indices[t + 1]]), dvec3(positions[indices[t + 2]])));
  return six_v / 6.0;
}

}  // namespace habuffer
