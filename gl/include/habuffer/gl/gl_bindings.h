// Where the GPU path's buffers are bound. Host apps choose the points so our
// buffers do not collide with theirs; the GLSL module is assembled with the
// same numbers (#define HA_BINDING_*), so a host shader and GlHaBuffer::bind()
// always agree.
#pragma once

#include <array>
#include <string>

namespace habuffer::gl {

struct GlBindings {
  // Shader-storage binding points.
  unsigned table = 0;
  unsigned max_age = 1;
  unsigned offsets = 2;
  unsigned counters = 3;
  unsigned locks = 4;    // emulated64 only
  unsigned capture = 5;
  unsigned stream = 6;   // the compute entry's input fragments, the resume pass's input calls
  unsigned deferred = 7; // insert calls cut short, appended for the resume pass
  unsigned saturation = 8;  // the saturation depth image (early cull with saturation)
  // Uniform-buffer binding point of the parameters block.
  unsigned params = 0;

  [[nodiscard]] std::array<unsigned, 9> storage_points() const {
    return {table, max_age, offsets, counters, locks, capture, stream, deferred, saturation};
  }
  // Throws GlError when two storage points coincide or a point is at or beyond
  // the context's limits (GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS,
  // GL_MAX_UNIFORM_BUFFER_BINDINGS); needs a current context.
  void validate() const;
  // "#define HA_BINDING_TABLE 0\n..." for the module assembly.
  [[nodiscard]] std::string glsl_defines() const;
};

}  // namespace habuffer::gl
