#include "habuffer/solids.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace habuffer {
namespace {

constexpr float kPi = 3.14159265358979f;

// A grid of (u, v) samples, u periodic, wrapped into quads (two triangles
// each, counter-clockwise seen from outside when `point` turns that way).
template <class Point>
void wrap_grid(Mesh& m, std::uint32_t nu, std::uint32_t nv, bool v_periodic, Point point) {
  const std::uint32_t rows = v_periodic ? nv : nv + 1;
  for (std::uint32_t j = 0; j < rows; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) m.positions.push_back(point(i, j));
  const auto at = [&](std::uint32_t i, std::uint32_t j) { return (j % rows) * nu + i % nu; };
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
}

}  // namespace

Mesh box_mesh(glm::vec3 lo, glm::vec3 hi, std::string name) {
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    throw std::invalid_argument("box " + name + ": every side must be positive");
  Mesh m;
  m.name = std::move(name);
  m.opacity = 1.0f;
  for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  // Each face counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
  m.indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
               2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
  return m;
}

Mesh sphere_mesh(glm::vec3 centre, float radius, std::uint32_t slices, std::uint32_t stacks, std::string name) {
  if (!(radius > 0.0f) || slices < 3 || stacks < 2)
    throw std::invalid_argument("sphere " + name + ": radius must be positive, slices at least 3, stacks at least 2");
  Mesh m;
  m.name = std::move(name);
  m.opacity = 1.0f;
  // Rows from the south pole (j = 0) to the north (j = stacks); the poles
  // repeated per slice (degenerate triangles there have no area).
  wrap_grid(m, slices, stacks, false, [&](std::uint32_t i, std::uint32_t j) {
    const float phi = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(slices);
    const float theta = kPi * static_cast<float>(j) / static_cast<float>(stacks) - 0.5f * kPi;
    // The poles exact: float's cos(-pi/2) is -4.4e-8, not 0, which would make
    // the pole a tiny mirrored ring and its "degenerate" triangles slivers
    // facing inward (a ray along the axis then crossed them).
    const float ring = j == 0 || j == stacks ? 0.0f : std::cos(theta);
    const float height = j == 0 ? -1.0f : j == stacks ? 1.0f : std::sin(theta);
    return centre + radius * glm::vec3(ring * std::cos(phi), ring * std::sin(phi), height);
  });
  return m;
}

Mesh cylinder_mesh(glm::vec3 base, glm::vec3 axis, float length, float radius, std::uint32_t sides,
                   std::string name) {
  const float axis_length = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  if (!(radius > 0.0f && length > 0.0f && axis_length > 0.0f) || sides < 3)
    throw std::invalid_argument("cylinder " + name + ": radius, length and axis must be positive, sides at least 3");
  const glm::vec3 w = axis / axis_length;
  const glm::vec3 helper = std::abs(w.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::vec3 u = glm::vec3(helper.y * w.z - helper.z * w.y, helper.z * w.x - helper.x * w.z, helper.x * w.y - helper.y * w.x);
  u /= std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
  const glm::vec3 v(w.y * u.z - w.z * u.y, w.z * u.x - w.x * u.z, w.x * u.y - w.y * u.x);  // u, v, w right-handed
  Mesh m;
  m.name = std::move(name);
  m.opacity = 1.0f;
  const glm::vec3 top = base + w * length;
  for (std::uint32_t i = 0; i < sides; ++i) {
    const float a = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(sides);
    const glm::vec3 r = radius * (std::cos(a) * u + std::sin(a) * v);
    m.positions.push_back(base + r);
    m.positions.push_back(top + r);
  }
  const auto centre_base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back(base);
  m.positions.push_back(top);
  for (std::uint32_t i = 0; i < sides; ++i) {
    const std::uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * ((i + 1) % sides), t1 = b1 + 1;
    m.indices.insert(m.indices.end(), {b0, b1, t1, b0, t1, t0});                  // the side, outward
    m.indices.insert(m.indices.end(), {centre_base, b1, b0});                    // the base cap, facing -w
    m.indices.insert(m.indices.end(), {centre_base + 1, t0, t1});                // the top cap, facing +w
  }
  return m;
}

Mesh torus_mesh(glm::vec3 centre, float major, float minor, std::uint32_t rings, std::uint32_t sides, std::string name) {
  if (!(minor > 0.0f && major > minor) || rings < 3 || sides < 3)
    throw std::invalid_argument("torus " + name + ": need 0 < minor < major radius and at least 3 rings and sides");
  Mesh m;
  m.name = std::move(name);
  m.opacity = 1.0f;
  wrap_grid(m, rings, sides, true, [&](std::uint32_t i, std::uint32_t j) {
    const float phi = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(rings);
    const float theta = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(sides);
    const float r = major + minor * std::cos(theta);
    return centre + glm::vec3(r * std::cos(phi), r * std::sin(phi), minor * std::sin(theta));
  });
  return m;
}

}  // namespace habuffer
