#include "habuffer/transmittance_reference.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace habuffer {
namespace {

constexpr std::uint32_t kLeafTriangles = 4;

// Whether the segment (origin, 1 / direction, length) meets the box.
bool meets(glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 origin, glm::dvec3 inverse, double length) {
  double near = 0.0, far = length;
  for (int k = 0; k < 3; ++k) {
    double t0 = (lo[k] - origin[k]) * inverse[k], t1 = (hi[k] - origin[k]) * inverse[k];
    if (std::isnan(t0) || std::isnan(t1)) {  // parallel to the slab, on its plane: inside it or not
      if (origin[k] < lo[k] || origin[k] > hi[k]) return false;
      continue;
    }
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return false;
  }
  return true;
}

}  // namespace

TransmittanceReference::TransmittanceReference(const Scene& scene) {
  for (std::uint32_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    const Mesh& m = scene.meshes[mesh];
    const double alpha = m.opacity >= 1.0f ? 1.0 : std::round(std::clamp(double(m.opacity), 0.0, 1.0) * 255.0) / 255.0;
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      const glm::dvec3 a(m.positions.at(m.indices[i])), b(m.positions.at(m.indices[i + 1])),
          c(m.positions.at(m.indices[i + 2]));
      triangles_.push_back({a, b - a, c - a, alpha, static_cast<std::uint32_t>(triangles_.size()), mesh});
    }
  }
  const Bounds bounds = scene.bounds();
  if (!bounds.empty()) {
    scene_lo_ = glm::dvec3(bounds.lo);
    scene_hi_ = glm::dvec3(bounds.hi);
  }
  if (!triangles_.empty()) build(0, static_cast<std::uint32_t>(triangles_.size()));
}

std::uint32_t TransmittanceReference::build(std::uint32_t first, std::uint32_t count) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  glm::dvec3 clo = lo, chi = hi;  // centroid bounds
  for (std::uint32_t i = first; i < first + count; ++i) {
    const Triangle& t = triangles_[i];
    for (const glm::dvec3 p : {t.a, t.a + t.e1, t.a + t.e2}) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const glm::dvec3 c = t.a + (t.e1 + t.e2) / 3.0;
    clo = glm::min(clo, c);
    chi = glm::max(chi, c);
  }
  nodes_[index] = {lo, hi, first, count, 0};
  if (count <= kLeafTriangles) return index;
  const glm::dvec3 extent = chi - clo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const auto middle = triangles_.begin() + first + count / 2;
  std::nth_element(triangles_.begin() + first, middle, triangles_.begin() + first + count,
                   [axis](const Triangle& a, const Triangle& b) {
                     return (3.0 * a.a + a.e1 + a.e2)[axis] < (3.0 * b.a + b.e1 + b.e2)[axis];
                   });
  const std::uint32_t left = build(first, count / 2);
  const std::uint32_t right = build(first + count / 2, count - count / 2);
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_[index].right = right;
  return index;
}

TransmittanceReference::Segment TransmittanceReference::segment_to_light(glm::dvec3 point,
                                                                         const LightView& light) const {
  if (!light.orthographic) {
    const glm::dvec3 to = glm::dvec3(light.position) - point;
    const double length = glm::length(to);
    return {point, length > 0.0 ? to / length : glm::dvec3(0.0, 0.0, 1.0), length};
  }
  // Against the light's direction, past the scene's bounds from anywhere inside them.
  const double reach = glm::length(scene_hi_ - scene_lo_) + glm::length(point - (scene_lo_ + scene_hi_) * 0.5) + 1.0;
  return {point, -glm::normalize(glm::dvec3(light.direction)), reach};
}

double TransmittanceReference::hit(const Triangle& t, const Segment& s, bool* toward) {
  // Moller-Trumbore, two-sided, in double.
  const glm::dvec3 p = glm::cross(s.direction, t.e2);
  const double det = glm::dot(t.e1, p);
  if (det == 0.0) return -1.0;  // parallel (or degenerate): the segment grazes it
  const double inv = 1.0 / det;
  const glm::dvec3 to = s.origin - t.a;
  const double u = glm::dot(to, p) * inv;
  if (u < 0.0 || u > 1.0) return -1.0;
  const glm::dvec3 q = glm::cross(to, t.e1);
  const double v = glm::dot(s.direction, q) * inv;
  if (v < 0.0 || u + v > 1.0) return -1.0;
  const double d = glm::dot(t.e2, q) * inv;
  if (toward) *toward = det < 0.0;  // its normal e1 x e2 points along the segment
  return d <= s.length ? d : -1.0;
}

namespace {

void check_self_distance(double self_distance) {
  if (!(self_distance >= 0.0 && std::isfinite(self_distance)))
    throw std::invalid_argument("transmittance reference: self distance " + std::to_string(self_distance) +
                                " is not a finite number >= 0");
}

}  // namespace

template <class Visit>
void TransmittanceReference::for_each_leaf(const Segment& s, Visit visit) const {
  if (nodes_.empty()) return;
  const glm::dvec3 inverse = 1.0 / s.direction;
  std::vector<std::uint32_t> stack = {0};
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (!meets(n.lo, n.hi, s.origin, inverse, s.length)) continue;
    if (n.count == 0) {
      stack.push_back(n.first);
      stack.push_back(n.right);
      continue;
    }
    if (!visit(n.first, n.first + n.count)) return;
  }
}

double TransmittanceReference::transmittance(glm::dvec3 point, const LightView& light, double self_distance) const {
  check_self_distance(self_distance);
  const Segment s = segment_to_light(point, light);
  double t = 1.0;
  for_each_leaf(s, [&](std::uint32_t first, std::uint32_t end) {
    for (std::uint32_t i = first; i < end; ++i)
      if (hit(triangles_[i], s) > self_distance) t *= 1.0 - triangles_[i].alpha;
    return t > 0.0;  // nothing passes an opaque hit: stop
  });
  return t;
}

std::vector<TransmittanceReference::Hit> TransmittanceReference::hits(glm::dvec3 point, const LightView& light) const {
  std::vector<Hit> out;
  const Segment s = segment_to_light(point, light);
  for_each_leaf(s, [&](std::uint32_t first, std::uint32_t end) {
    for (std::uint32_t i = first; i < end; ++i) {
      bool toward = false;
      if (const double d = hit(triangles_[i], s, &toward); d >= 0.0)
        out.push_back({d, triangles_[i].alpha, triangles_[i].id, toward, triangles_[i].mesh});
    }
    return true;
  });
  std::sort(out.begin(), out.end(), [](const Hit& a, const Hit& b) { return a.distance < b.distance; });
  return out;
}

std::vector<TransmittanceReference::Hit> TransmittanceReference::crossings(glm::dvec3 point, const LightView& light,
                                                                          double same) const {
  const std::vector<Hit> all = hits(point, light);
  std::vector<Hit> out;
  for (const Hit& h : all) {
    bool repeat = false;
    for (auto g = out.rbegin(); g != out.rend() && h.distance - g->distance <= same; ++g)
      repeat = repeat || (g->mesh == h.mesh && g->toward == h.toward);
    if (!repeat) out.push_back(h);
  }
  return out;
}

double TransmittanceReference::transmittance_brute_force(glm::dvec3 point, const LightView& light,
                                                         double self_distance) const {
  check_self_distance(self_distance);
  const Segment s = segment_to_light(point, light);
  double t = 1.0;
  for (const Triangle& tri : triangles_) {
    const double d = hit(tri, s);
    if (d > self_distance) t *= 1.0 - tri.alpha;
  }
  return t;
}

}  // namespace habuffer
