#include "heat_overlay.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "habuffer/gl/gl_buffer.h"
#include "view_shaders.h"

namespace habuffer::view {

HeatOverlay::HeatOverlay()
    : program_(gl::ShaderProgram::graphics(kOverlayVertex, kOverlayFragment, "habuffer-view heat map")) {
  glCreateVertexArrays(1, &vertex_array_);
}

HeatOverlay::~HeatOverlay() {
  glDeleteVertexArrays(1, &vertex_array_);
  gl::delete_buffer(upload_);
}

void HeatOverlay::draw(unsigned buffer, std::uint32_t first, std::uint32_t stride, Extent screen, double full,
                       ViewRect viewport) {
  program_.set("v_screen", screen.x, screen.y);
  program_.set("v_first", first);
  program_.set("v_stride", stride);
  program_.set("v_scale", static_cast<float>(1.0 / std::max(full, 1.0)));
  program_.set("v_alpha", 0.6f);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  glViewport(viewport.x, viewport.y, static_cast<GLsizei>(viewport.size.x), static_cast<GLsizei>(viewport.size.y));
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_.id());
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
}

void HeatOverlay::draw(const std::vector<std::uint32_t>& values, Extent screen, double full, ViewRect viewport) {
  if (values.size() != upload_words_) {
    gl::delete_buffer(upload_);
    upload_ = gl::create_buffer(std::max<std::uint64_t>(values.size(), 1) * sizeof(std::uint32_t));
    upload_words_ = values.size();
  }
  if (!values.empty())
    glNamedBufferSubData(upload_, 0, static_cast<GLsizeiptr>(values.size() * sizeof(std::uint32_t)), values.data());
  draw(upload_, 0, 1, screen, full, viewport);
}

}  // namespace habuffer::view
