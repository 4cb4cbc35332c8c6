// Saves the GL state the library's passes touch and restores it on scope
// exit, so a host app's context is left as it was: current program, vertex
// array, draw framebuffer, viewport, polygon mode, the capabilities a
// full-screen pass must switch off, and the buffer bindings at our points.
#pragma once

#include <array>
#include <vector>

#include <epoxy/gl.h>

#include "habuffer/gl/gl_bindings.h"

namespace habuffer::gl {

class GlStateGuard {
 public:
  explicit GlStateGuard(const GlBindings& bindings);
  ~GlStateGuard();
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  // The capabilities full-screen passes disable (GL_BLEND, GL_DEPTH_TEST, ...).
  static const std::array<GLenum, 6>& pass_capabilities();
  // Disables them and sets polygon mode to fill (restored by the destructor).
  static void prepare_full_screen_pass();

 private:
  struct IndexedBuffer {
    GLenum target;
    GLuint index;
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
  };
  GLint program_ = 0, vertex_array_ = 0, draw_framebuffer_ = 0;
  GLint viewport_[4] = {};
  GLint polygon_mode_[2] = {};
  std::array<GLboolean, 6> enabled_{};
  std::vector<IndexedBuffer> indexed_;
  GLint storage_generic_ = 0, uniform_generic_ = 0;
};

}  // namespace habuffer::gl
