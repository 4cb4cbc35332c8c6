#include "gl_state_guard.h"

namespace habuffer::gl {

const std::array<GLenum, 6>& GlStateGuard::pass_capabilities() {
  static const std::array<GLenum, 6> caps{GL_BLEND,        GL_DEPTH_TEST,   GL_STENCIL_TEST,
                                          GL_CULL_FACE,    GL_SCISSOR_TEST, GL_RASTERIZER_DISCARD};
  return caps;
}

void GlStateGuard::prepare_full_screen_pass() {
  for (GLenum cap : pass_capabilities()) glDisable(cap);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

GlStateGuard::GlStateGuard(const GlBindings& bindings) {
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);
  for (std::size_t i = 0; i < enabled_.size(); ++i) enabled_[i] = glIsEnabled(pass_capabilities()[i]);
  for (unsigned p : bindings.storage_points()) indexed_.push_back({GL_SHADER_STORAGE_BUFFER, p});
  indexed_.push_back({GL_UNIFORM_BUFFER, bindings.params});
  for (IndexedBuffer& b : indexed_) {
    const bool storage = b.target == GL_SHADER_STORAGE_BUFFER;
    glGetIntegeri_v(storage ? GL_SHADER_STORAGE_BUFFER_BINDING : GL_UNIFORM_BUFFER_BINDING, b.index, &b.buffer);
    glGetInteger64i_v(storage ? GL_SHADER_STORAGE_BUFFER_START : GL_UNIFORM_BUFFER_START, b.index, &b.start);
    glGetInteger64i_v(storage ? GL_SHADER_STORAGE_BUFFER_SIZE : GL_UNIFORM_BUFFER_SIZE, b.index, &b.size);
  }
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_generic_);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_generic_);
}

GlStateGuard::~GlStateGuard() {
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vertex_array_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode_[0]));
  for (std::size_t i = 0; i < enabled_.size(); ++i)
    (enabled_[i] != GL_FALSE ? glEnable : glDisable)(pass_capabilities()[i]);
  for (const IndexedBuffer& b : indexed_) {
    if (b.size > 0)
      glBindBufferRange(b.target, b.index, static_cast<GLuint>(b.buffer), b.start, b.size);
    else
      glBindBufferBase(b.target, b.index, static_cast<GLuint>(b.buffer));
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(storage_generic_));
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(uniform_generic_));
}

}  // namespace habuffer::gl
