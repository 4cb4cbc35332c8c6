/// @file
/// A scene's meshes in vertex buffers, drawn by a program of the render
/// shaders' interface (r_view, r_projection, r_near, r_far, r_colour,
/// r_opacity): the host side of habuffer-view, plain OpenGL 4.5.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/camera.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/scene.h"

namespace habuffer::view {

/// The meshes of one scene on the GPU (needs a current OpenGL 4.5 context).
class GpuMeshes {
 public:
  explicit GpuMeshes(const Scene& scene);
  ~GpuMeshes();
  GpuMeshes(const GpuMeshes&) = delete;
  GpuMeshes& operator=(const GpuMeshes&) = delete;

  /// Draws the opaque meshes (`opaque`) or the transparent ones with
  /// `program`, seen by `camera`; leaves no program or vertex array bound.
  void draw(const gl::ShaderProgram& program, const Camera& camera, bool opaque) const;

 private:
  struct Mesh {
    unsigned vertex_array = 0, vertices = 0, indices = 0;
    std::int32_t count = 0;
    glm::vec3 colour;
    float opacity;
    bool opaque;
  };
  std::vector<Mesh> meshes_;
};

}  // namespace habuffer::view
