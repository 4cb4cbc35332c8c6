// The camera of `habuffer render`: orbits the scene's bounds (yaw, pitch)
// and frames them, with near and far planes tight around the bounding
// sphere, so the linear eye depth maps to t in [0, 1] as in the paper.
#pragma once

#include <glm/mat4x4.hpp>

#include "habuffer/extent.h"
#include "habuffer/scene.h"

namespace habuffer {

struct CameraParams {
  float yaw = 30.0f;    // degrees around the vertical axis
  float pitch = 20.0f;  // degrees above the horizontal
  float fov = 45.0f;    // degrees, of the narrower side of the screen
};

struct Camera {
  glm::mat4 view{1.0f}, projection{1.0f};
  float near_plane = 0.1f, far_plane = 1.0f;
  // t of a point at eye-space z (negative in front of the camera).
  [[nodiscard]] float depth(float eye_z) const { return (-eye_z - near_plane) / (far_plane - near_plane); }
};

// Throws SceneError for an empty scene or parameters out of range.
Camera frame_scene(const Scene& scene, const CameraParams& params, Extent screen);

}  // namespace habuffer
