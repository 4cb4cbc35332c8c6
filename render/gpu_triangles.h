/// @file
/// Triangles on the GPU for the render library's own passes (the voxelizer,
/// CSG): positions and indices in storage buffers and one vertex array
/// (attribute 0, a vec3 position). Private to the render library.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include <glm/vec3.hpp>

#include "habuffer/gl/gl_buffer.h"

namespace habuffer {

/// See the file comment; needs a current OpenGL 4.5 context.
class GpuTriangles {
 public:
  GpuTriangles(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices);
  ~GpuTriangles();
  GpuTriangles(GpuTriangles&& o) noexcept;
  GpuTriangles(const GpuTriangles&) = delete;
  GpuTriangles& operator=(const GpuTriangles&) = delete;
  GpuTriangles& operator=(GpuTriangles&&) = delete;

  /// Draws every triangle with the bound program (the vertex array bound for the call only).
  void draw() const;

 private:
  gl::GlStorage vertices_, elements_;
  unsigned array_ = 0;
  std::int32_t count_ = 0;
};

/// The samples `draw` rasterizes (an occlusion query around it): the
/// fragments of a counting pass, from which a table is sized once.
std::uint64_t count_samples(const std::function<void()>& draw);

/// A fragment shader that writes nothing: with a scene's vertex shader, the counting pass.
inline constexpr const char* kCountingFragment = "#version 450 core\nvoid main() {}\n";

}  // namespace habuffer
