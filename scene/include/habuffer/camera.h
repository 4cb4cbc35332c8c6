/// @file
/// The camera of `habuffer render`: orbits the scene's bounds (yaw, pitch)
/// and frames them, with near and far planes tight around the bounding
/// sphere, so the linear eye depth maps to t in [0, 1] as in the paper.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "habuffer/extent.h"
#include "habuffer/scene.h"

namespace habuffer {

/// The camera's range, one rule for render, csg and the viewer: pitch in
/// [-kMaxPitch, kMaxPitch], fov in the open interval (kMinFov, kMaxFov) degrees.
inline constexpr float kMaxPitch = 90.0f;
inline constexpr float kMinFov = 1.0f;
inline constexpr float kMaxFov = 179.0f;

/// Where `habuffer render` looks from (--yaw, --pitch, --fov).
struct CameraParams {
  float yaw = 30.0f;    ///< degrees around the vertical axis
  float pitch = 20.0f;  ///< degrees above the horizontal
  float fov = 45.0f;    ///< degrees, of the narrower side of the screen
};

/// A framed camera (frame_scene makes one).
struct Camera {
  glm::mat4 view{1.0f}, projection{1.0f};  ///< world to eye, eye to clip
  float near_plane = 0.1f, far_plane = 1.0f;  ///< eye-space distances that map to t = 0 and t = 1
  /// t of a point at eye-space z (negative in front of the camera).
  [[nodiscard]] float depth(float eye_z) const { return (-eye_z - near_plane) / (far_plane - near_plane); }
};

/// Sets `camera`'s near and far planes to hug every vertex of `scene` along
/// its view (2% of the extent outside it; near at least 1e-4), so t spans
/// [0, 1] over the scene: orthographic cameras and lights.
void fit_depth_range(const Scene& scene, Camera& camera);

/// The camera orbiting `scene`'s bounds at `params`, framed for `screen` (orthographic scenes along -z).
/// Throws SceneError for an empty scene or screen, or parameters out of range
/// (fov in (1, 179), pitch in [-90, 90] degrees, yaw finite).
Camera frame_scene(const Scene& scene, const CameraParams& params, Extent screen);

/// The world point that `camera`, seeing a `screen` of pixels, shows at
/// window position `window` (pixels from the bottom left: a pixel's centre
/// is its index + 0.5) and depth t, in double: the inverse of rasterizing
/// it (perspective and orthographic alike).
glm::dvec3 unproject(const Camera& camera, Extent screen, glm::dvec2 window, double t);

}  // namespace habuffer
