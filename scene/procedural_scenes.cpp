#include "habuffer/procedural_scenes.h"

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "habuffer/random.h"

namespace habuffer {
namespace {

constexpr float kPi = 3.14159265358979f;

float uniform(SplitMix64& rng) { return static_cast<float>(rng.next() >> 40) * 0x1.0p-24f; }

glm::vec3 in_unit_ball(SplitMix64& rng) {
  for (;;) {
    const glm::vec3 p(uniform(rng) * 2 - 1, uniform(rng) * 2 - 1, uniform(rng) * 2 - 1);
    if (glm::dot(p, p) <= 1.0f) return p;
  }
}

glm::vec3 hue(float h) {
  const glm::vec3 k = glm::abs(glm::fract(glm::vec3(h) + glm::vec3(0.0f, 2.0f / 3.0f, 1.0f / 3.0f)) * 6.0f - 3.0f);
  return glm::clamp(k - 1.0f, 0.0f, 1.0f) * 0.75f + 0.2f;
}

// A tube of `sides` faces swept along `path`, appended to `mesh`.
void sweep_tube(Mesh& mesh, const std::vector<glm::vec3>& path, float radius, std::uint32_t sides) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const glm::vec3 along = glm::normalize(path[std::min(i + 1, path.size() - 1)] - path[i > 0 ? i - 1 : 0]);
    const glm::vec3 helper = std::abs(along.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(along, helper)), v = glm::cross(along, u);
    for (std::uint32_t k = 0; k < sides; ++k) {
      const float a = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(sides);
      mesh.positions.push_back(path[i] + radius * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  for (std::uint32_t i = 0; i + 1 < path.size(); ++i)
    for (std::uint32_t k = 0; k < sides; ++k) {
      const std::uint32_t a = base + i * sides + k, b = base + i * sides + (k + 1) % sides;
      const std::uint32_t c = a + sides, d = b + sides;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
}

// A random walk that stays inside the unit ball.
std::vector<glm::vec3> random_strand(SplitMix64& rng, std::uint32_t segments, float step) {
  std::vector<glm::vec3> path{in_unit_ball(rng) * 0.9f};
  glm::vec3 dir = glm::normalize(in_unit_ball(rng) + glm::vec3(1e-3f));
  for (std::uint32_t s = 0; s < segments; ++s) {
    dir = glm::normalize(dir + 0.6f * in_unit_ball(rng));
    glm::vec3 next = path.back() + step * dir;
    if (glm::length(next) > 1.0f) {
      dir = -dir;
      next = path.back() + step * dir;
    }
    path.push_back(next);
  }
  return path;
}

Mesh quad(glm::vec2 centre, float half, float z, glm::vec3 colour, float opacity, std::string name) {
  Mesh m;
  m.name = std::move(name);
  m.colour = colour;
  m.opacity = opacity;
  m.positions = {{centre.x - half, centre.y - half, z}, {centre.x + half, centre.y - half, z},
                 {centre.x + half, centre.y + half, z}, {centre.x - half, centre.y + half, z}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

}  // namespace

Scene make_hairball(std::uint32_t tubes, std::uint64_t seed, float opacity) {
  constexpr std::uint32_t kGroups = 8, kSegments = 24, kSides = 4;
  Scene s;
  s.name = "hairball";
  s.meshes.resize(kGroups);
  for (std::uint32_t g = 0; g < kGroups; ++g) {
    s.meshes[g].name = "strands " + std::to_string(g);
    s.meshes[g].colour = hue(static_cast<float>(g) / kGroups);
    s.meshes[g].opacity = opacity;
  }
  SplitMix64 rng(seed);
  for (std::uint32_t t = 0; t < tubes; ++t) sweep_tube(s.meshes[t % kGroups], random_strand(rng, kSegments, 0.09f), 0.004f, kSides);
  return s;
}

Scene make_quads(std::uint32_t quads, float spread, std::uint64_t seed, float opacity) {
  constexpr float kHalf = 0.25f;  // every quad is a quarter of the view wide
  Scene s;
  s.name = "quads";
  s.orthographic_half = 1.0f;
  s.default_yaw = s.default_pitch = 0.0f;
  SplitMix64 rng(seed);
  for (std::uint32_t i = 0; i < quads; ++i) {
    const glm::vec2 centre(spread * (uniform(rng) * 2 - 1) * (1 - kHalf), spread * (uniform(rng) * 2 - 1) * (1 - kHalf));
    const float z = uniform(rng) * 1.8f - 0.9f;
    s.meshes.push_back(quad(centre, kHalf, z, hue(uniform(rng)), opacity, "quad " + std::to_string(i)));
  }
  return s;
}

Scene make_planes(std::uint32_t planes, PlaneOrder order, float opacity) {
  Scene s;
  s.name = "planes";
  s.orthographic_half = 1.0f;
  s.default_yaw = s.default_pitch = 0.0f;
  for (std::uint32_t k = 0; k < planes; ++k) {
    // Plane k at depth rank k from the front (z = +0.9 nearest the camera).
    const std::uint32_t i = order == PlaneOrder::FrontToBack ? k : planes - 1 - k;
    const float z = 0.9f - 1.8f * (static_cast<float>(i) + 0.5f) / static_cast<float>(planes);
    // Half-side 8: the plane covers the view up to an aspect ratio of 8.
    s.meshes.push_back(quad({0.0f, 0.0f}, 8.0f, z, hue(static_cast<float>(i) / static_cast<float>(planes)), opacity,
                            "plane " + std::to_string(i)));
  }
  return s;
}

}  // namespace habuffer
