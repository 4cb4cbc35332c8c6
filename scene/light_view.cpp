#include "habuffer/light_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "habuffer/glsl_env.h"
#include <glm/gtc/matrix_transform.hpp>

namespace habuffer {
namespace {

constexpr float kMargin = 1.02f;  // the frustum a little outside the bounding sphere and the depth extent

std::string text(glm::vec3 v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// An up vector not parallel to `dir`.
glm::vec3 up_for(glm::vec3 dir) {
  return std::abs(dir.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// `d` over its largest component's magnitude, then normalised: any finite
// vector but zero has a direction, however large or small (1e38 or 1e-40
// would overflow or underflow the squared length of glm::normalize).
glm::vec3 unit_direction(glm::vec3 d) {
  const float largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  return glm::normalize(d / largest);
}

void check_params(const LightParams& p) {
  const glm::vec3 d = p.direction;
  if (p.orthographic && !(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)))
    throw SceneError("light direction " + text(d) + " is not finite");
  if (p.orthographic && d == glm::vec3(0.0f)) throw SceneError("light direction " + text(d) + " is the zero vector");
  if (p.size.area() == 0) throw SceneError("light map size " + p.size.str() + " has no pixels");
  if (!p.orthographic) {
    if (!(p.fov > 1.0f && p.fov < 179.0f))
      throw SceneError("light fov " + std::to_string(p.fov) + " is not in (1, 179) degrees");
    if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) || !std::isfinite(p.position.z))
      throw SceneError("light position " + text(p.position) + " is not finite");
  }
}

std::string light_name(const LightParams& p) {
  return std::string("light ") + (p.orthographic ? "direction " + text(p.direction) : "position " + text(p.position));
}

// The frustum must leave float32 a depth range to work in (as the view's
// camera, camera.cpp): a light very far from a small scene has near and far
// equal in float32, and t would be 0 / 0.
void check_light_range(const LightParams& p, const LightView& v) {
  const float near = v.camera.near_plane, far = v.camera.far_plane;
  bool finite = std::isfinite(near) && std::isfinite(far);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(v.camera.view[c][r]) && std::isfinite(v.camera.projection[c][r]);
  if (finite && far - near > far * 0x1.0p-20f && (p.orthographic || near > 0.0f)) return;
  throw SceneError(light_name(p) + " leaves no usable depth range over the scene in float32 (near " +
                   std::to_string(near) + ", far " + std::to_string(far) + "): bring the light closer to the scene");
}

// The precision rule (light_view.h, kLightDepthRounding): float32 rounds the
// light's depth by up to 4 ulps of the largest coordinate its view
// transform handles; beyond one light pixel's side at the far plane the
// bias no longer keeps surfaces from shadowing themselves. `reach`: the
// scene's farthest point from the origin.
void check_light_precision(const LightParams& p, const LightView& v, double reach) {
  const glm::vec4 origin = v.camera.view[3];  // the world origin in the light's eye space: as far as the eye from it
  const double eye = glm::length(glm::dvec3(origin.x, origin.y, origin.z));
  const double largest = std::max({eye, reach, double{v.camera.far_plane}});
  const double side = v.pixel_world_size(1.0f);
  if (largest * kLightDepthRounding <= side) return;
  throw SceneError(light_name(p) + " leaves float32 too coarse a depth for this scene: the light's view handles "
                   "coordinates up to " + number(largest) + " (its eye " + number(eye) + " and the scene's farthest "
                   "point " + number(reach) + " from the origin), which float32 rounds by up to " +
                   number(largest * kLightDepthRounding) + " (4 ulps), more than one light pixel's side at the far "
                   "plane (" + number(side) + "), so surfaces would shadow themselves at random: keep the light and "
                   "the scene within " + number(side / kLightDepthRounding) + " of the origin (2^21 light pixels) "
                   "or use a smaller light map than " + p.size.str());
}

}  // namespace

LightParams spot_along(const Scene& scene, glm::vec3 direction, float fov, Extent size) {
  LightParams p;
  p.direction = direction;
  p.fov = fov;
  p.size = size;
  check_params(p);  // orthographic: checks the direction
  p.orthographic = false;
  check_params(p);  // a spot: checks the fov
  const Bounds b = scene.bounds();
  if (b.empty()) throw SceneError("scene '" + scene.name + "' has no vertices to light");
  const glm::vec3 centre = b.centre();
  const float r = std::max(scene.radius_around(centre), 1e-6f);
  const float touching = r * kMargin / std::sin(glm::radians(fov) / 2.0f);
  p.position = centre - unit_direction(direction) * (1.5f * touching);
  return p;
}

LightView frame_light(const Scene& scene, const LightParams& params) {
  check_params(params);
  const Bounds b = scene.bounds();
  if (b.empty()) throw SceneError("scene '" + scene.name + "' has no vertices to light");
  const glm::vec3 centre = b.centre();
  // A spot looks at the scene's centre: its direction is that, whatever `direction` says.
  const glm::vec3 dir =
      params.orthographic ? unit_direction(params.direction) : glm::normalize(centre - params.position);
  const float r = std::max(scene.radius_around(centre), 1e-6f);
  const double reach = glm::length(glm::dvec3(centre)) + double{r};  // at least the scene's farthest point's distance
  const float aspect = static_cast<float>(params.size.x) / static_cast<float>(params.size.y);
  LightView v;
  v.size = params.size;
  v.orthographic = params.orthographic;
  v.direction = dir;
  v.position = params.position;
  if (params.orthographic) {
    v.camera.view = glm::lookAt(centre - dir * (2.0f * r), centre, up_for(dir));
    fit_depth_range(scene, v.camera);
    const float half = r * kMargin, hx = aspect >= 1.0f ? half * aspect : half, hy = aspect >= 1.0f ? half : half / aspect;
    v.camera.projection = glm::ortho(-hx, hx, -hy, hy, v.camera.near_plane, v.camera.far_plane);
    check_light_range(params, v);
    check_light_precision(params, v, reach);
    return v;
  }
  const float distance = glm::length(centre - params.position);
  if (!(distance > r * kMargin))
    throw SceneError("light position " + text(params.position) + " is inside the scene's bounding sphere (centre " +
                     text(centre) + ", radius " + std::to_string(r) + "): a spot must see the scene from outside");
  const float half_needed = std::asin(std::min(1.0f, r * kMargin / distance));
  if (2.0f * half_needed > glm::radians(params.fov))
    throw SceneError("light fov " + std::to_string(params.fov) + " cannot hold the scene from " + text(params.position) +
                     " (it needs " + std::to_string(glm::degrees(2.0f * half_needed)) + " degrees)");
  const glm::vec3 towards = glm::normalize(centre - params.position);
  v.camera.view = glm::lookAt(params.position, centre, up_for(towards));
  fit_depth_range(scene, v.camera);
  const float fovy = aspect >= 1.0f ? 2.0f * half_needed : 2.0f * std::atan(std::tan(half_needed) / aspect);
  check_light_range(params, v);  // before the projection divides by far - near
  v.camera.projection = glm::perspective(fovy, aspect, v.camera.near_plane, v.camera.far_plane);
  check_light_range(params, v);
  check_light_precision(params, v, reach);
  return v;
}

namespace {

// shared/ha_light_map.glsl compiled as C++: the mapping the GPU lookup runs.
struct LightMap {
  HABUFFER_GLSL_CLASS_PRELUDE
  using vec2 = glm::vec2;
  using mat4 = glm::mat4;
#include "habuffer/shared/ha_light_map.glsl"
};

}  // namespace

std::optional<LightSample> LightView::sample(glm::vec3 p) const {
  glm::vec2 window{0.0f};
  float t = 0.0f;
  LightMap map;
  if (!map.habuffer_light_map(camera.view, camera.projection, glm::vec2(size.x, size.y), camera.near_plane,
                              camera.far_plane, p, window, t))
    return std::nullopt;
  return LightSample{glm::uvec2(static_cast<std::uint32_t>(window.x), static_cast<std::uint32_t>(window.y)), t, window};
}

float LightView::pixel_world_size(float t) const {
  // Orthographic: 2 / P[0][0] world units span the map's width; perspective:
  // the same at eye distance d is 2 d / P[0][0].
  const float width = 2.0f / camera.projection[0][0];
  const float d = camera.near_plane + t * (camera.far_plane - camera.near_plane);
  return (orthographic ? width : width * d) / static_cast<float>(size.x);
}

double shadow_slope_limit(Extent size) { return static_cast<double>(std::min(size.x, size.y)); }

std::uint32_t shadow_bias_codes(const LightView& light, float max_slope, std::uint32_t depth_bits) {
  if (!(std::isfinite(max_slope) && max_slope >= 0.0f))
    throw std::invalid_argument("shadow bias: max slope " + std::to_string(max_slope) + " is not a finite number >= 0");
  if (double{max_slope} >= shadow_slope_limit(light.size))
    throw std::invalid_argument("shadow bias: max slope " + number(max_slope) + " is not below " +
                                number(shadow_slope_limit(light.size)) + ", the light map " + light.size.str() +
                                "'s short side in pixels: the bias would exceed the whole scene's depth");
  if (depth_bits == 0 || depth_bits > 32)
    throw std::invalid_argument("shadow bias: " + std::to_string(depth_bits) + " depth bits outside 1..32");
  // The deepest point has the widest pixels under a spot: bias for t = 1.
  const double depth_step = double(max_slope) * light.pixel_world_size(1.0f);
  const double codes = depth_step / double(light.camera.far_plane - light.camera.near_plane) * std::ldexp(1.0, int(depth_bits));
  return static_cast<std::uint32_t>(std::min(std::ceil(codes), double(UINT32_MAX - 1))) + 1u;
}

}  // namespace habuffer
