#include "habuffer/camera.h"
#include "habuffer/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

namespace habuffer {
namespace {

constexpr float kMargin = 1.02f;  // near and far a little outside the bounding sphere

glm::vec3 orbit_direction(float yaw_deg, float pitch_deg) {
  const float yaw = glm::radians(yaw_deg), pitch = glm::radians(pitch_deg);
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

// The square [-half, half]^2 around the origin, seen from the orbit
// direction; near and far hug the scene's extent along the view, whatever
// the orientation, so nothing is clipped in depth and t spans [0, 1].
Camera orthographic(const Scene& scene, float half, const CameraParams& params, Extent screen) {
  const float aspect = static_cast<float>(screen.x) / static_cast<float>(screen.y);
  const float r = std::max(scene.radius_around(glm::vec3(0.0f)), half);
  const glm::vec3 eye = orbit_direction(params.yaw, params.pitch) * (2.0f * r);
  const glm::vec3 up = std::abs(params.pitch) > 89.0f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  Camera c;
  c.view = glm::lookAt(eye, glm::vec3(0.0f), up);
  fit_depth_range(scene, c);
  const float hx = aspect >= 1.0f ? half * aspect : half, hy = aspect >= 1.0f ? half : half / aspect;
  c.projection = glm::ortho(-hx, hx, -hy, hy, c.near_plane, c.far_plane);
  return c;
}

Camera perspective(const Bounds& b, float radius, const CameraParams& params, Extent screen) {
  const float aspect = static_cast<float>(screen.x) / static_cast<float>(screen.y);
  // Any positive size: scenes below float32's depth precision are refused
  // by check_depth_range rather than drawn as a dot of a floor size.
  const float r = std::max(radius, std::numeric_limits<float>::min());
  // The fov is the narrower side's: the bounding sphere fits both sides.
  const float half_narrow = glm::radians(params.fov) * 0.5f;
  const float distance = r / std::sin(half_narrow) * kMargin;
  const float fovy = aspect >= 1.0f ? 2.0f * half_narrow : 2.0f * std::atan(std::tan(half_narrow) / aspect);
  const glm::vec3 eye = b.centre() + orbit_direction(params.yaw, params.pitch) * distance;
  const glm::vec3 up = std::abs(params.pitch) > 89.0f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  Camera c;
  c.view = glm::lookAt(eye, b.centre(), up);
  c.near_plane = std::max(distance - r * kMargin, distance * 1e-3f);
  c.far_plane = distance + r * kMargin;
  c.projection = glm::perspective(fovy, aspect, c.near_plane, c.far_plane);
  return c;
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The depth t = (-z - near) / (far - near) needs a range that float32 can
// resolve: finite matrices, 0 < near < far, and far - near well above far's
// own rounding step (2^-20 of it keeps about a million distinct depths).
void check_depth_range(const Scene& scene, const Bounds& b, const Camera& c) {
  const bool usable = finite(c.view) && finite(c.projection) && std::isfinite(c.near_plane) &&
                      std::isfinite(c.far_plane) && c.near_plane > 0.0f &&
                      c.far_plane - c.near_plane > c.far_plane * 0x1.0p-20f &&
                      // a perspective's depth term 2 far near / (far - near) must not underflow
                      (c.projection[2][3] == 0.0f || std::abs(c.projection[3][2]) >= std::numeric_limits<float>::min());
  if (usable) return;
  const auto text = [](glm::vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
    return std::string(buf);
  };
  throw SceneError("scene '" + scene.name + "': its extent, " + text(b.lo) + " to " + text(b.hi) +
                   ", leaves no usable depth range in float32 (near " + shortest_text(c.near_plane) + ", far " +
                   shortest_text(c.far_plane) + "); coordinates must be finite and below about 1e18, the scene above "
                   "about 1e-18 across");
}

}  // namespace

void fit_depth_range(const Scene& scene, Camera& camera) {
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  for (const Mesh& m : scene.meshes)
    for (const glm::vec3& p : m.positions) {
      const float d = -(camera.view * glm::vec4(p, 1.0f)).z;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  const float margin = std::max(hi - lo, 1e-3f) * (kMargin - 1.0f);
  camera.near_plane = std::max(lo - margin, 1e-4f);
  camera.far_plane = hi + margin;
}

Camera frame_scene(const Scene& scene, const CameraParams& params, Extent screen) {
  if (!(params.fov > kMinFov && params.fov < kMaxFov))
    throw SceneError("--fov " + std::to_string(params.fov) + " is not in (1, 179) degrees");
  if (!std::isfinite(params.yaw)) throw SceneError("--yaw is not a finite angle");
  if (!(std::abs(params.pitch) <= kMaxPitch))
    throw SceneError("--pitch " + std::to_string(params.pitch) + " is not in [-90, 90] degrees");
  if (screen.area() == 0) throw SceneError("screen " + screen.str() + " has no pixels");
  const Bounds b = scene.bounds();
  if (b.empty()) throw SceneError("scene '" + scene.name + "' has no vertices");
  const Camera c = scene.orthographic_half ? orthographic(scene, *scene.orthographic_half, params, screen)
                                           : perspective(b, scene.radius_around(b.centre()), params, screen);
  check_depth_range(scene, b, c);
  return c;
}

}  // namespace habuffer

namespace habuffer {

glm::dvec3 unproject(const Camera& camera, Extent screen, glm::dvec2 window, double t) {
  const glm::dvec2 ndc = window / glm::dvec2(screen.x, screen.y) * 2.0 - 1.0;
  const glm::dmat4 inverse_projection = glm::inverse(glm::dmat4(camera.projection));
  const glm::dvec4 a4 = inverse_projection * glm::dvec4(ndc, -1.0, 1.0), b4 = inverse_projection * glm::dvec4(ndc, 1.0, 1.0);
  const glm::dvec3 a = glm::dvec3(a4) / a4.w, b = glm::dvec3(b4) / b4.w;  // the pixel's ray, near to far plane
  const double eye_z = -(double{camera.near_plane} + t * (double{camera.far_plane} - double{camera.near_plane}));
  const glm::dvec3 eye = a + (b - a) * ((eye_z - a.z) / (b.z - a.z));
  return glm::dvec3(glm::inverse(glm::dmat4(camera.view)) * glm::dvec4(eye, 1.0));
}

}  // namespace habuffer
