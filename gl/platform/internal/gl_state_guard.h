// Saves the GL state the library's passes touch and restores it on scope
// exit, so a host app's context is left as it was: current program, vertex
// array, draw framebuffer, viewport 0, polygon mode, the colour masks and
// blend setup of every draw buffer (the resolve writes buffer 0 and masks
// the others, wboit's gather writes buffers 0 and 1), the pixel-pack buffer and pack parameters (the
// blended baselines' copies), the capabilities a
// full-screen pass must switch off (per draw buffer and per viewport where GL
// keeps them so, the clip distances, logic op, program point size), the point size, the query-buffer binding, and the
// buffer bindings at our points.
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

  // Disables what would alter a full-screen pass (blend, depth, stencil,
  // cull, scissor, rasterizer discard, clip distances), sets polygon mode to
  // fill, enables every colour channel of draw buffer 0 (a mask the host left
  // off would make the resolve write nothing) and masks every other draw
  // buffer (the pass writes output 0 only: a host's second attachment, an id
  // buffer, would get undefined values), and unbinds the query buffer so
  // query results come back to memory.
  static void prepare_full_screen_pass();
  // Viewport 0 only (glViewport would reset every viewport of the host's array).
  static void set_viewport(GLsizei width, GLsizei height);
  // For a point draw that blends (the blended baselines' stream entry): what
  // prepare_full_screen_pass switches off except blending, and points of size 1.
  static void prepare_point_pass();
  // GL's initial pack parameters (tightly packed rows, no skips), so a read
  // into a buffer object lays the pixels out as they are.
  static void prepare_pack();

 private:
  struct IndexedBuffer {
    GLenum target;
    GLuint index;
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
  };
  struct Capability {
    GLenum cap;
    GLint index;  // -1: not indexed
    GLboolean enabled;
  };
  GLint program_ = 0, vertex_array_ = 0, draw_framebuffer_ = 0, query_buffer_ = 0;
  GLfloat viewport_[4] = {};
  GLint polygon_mode_[2] = {};
  GLfloat point_size_ = 1.0f;
  struct DrawBuffer {
    GLboolean mask[4] = {};  // colour write mask
    GLint blend[6] = {};     // blend functions and equations
  };
  std::vector<DrawBuffer> draw_buffers_;  // every draw buffer, GL_MAX_DRAW_BUFFERS of them
  GLint pack_buffer_ = 0;
  std::array<GLint, 8> pack_ = {};  // the pack parameters, in the order of kPackParameters
  std::vector<Capability> capabilities_;
  std::vector<IndexedBuffer> indexed_;
  GLint storage_generic_ = 0, uniform_generic_ = 0;
};

// Reads a query's 64-bit result into memory whatever GL_QUERY_BUFFER the
// host bound, and binds the host's query buffer again.
GLuint64 query_result(GLuint query);

}  // namespace habuffer::gl
