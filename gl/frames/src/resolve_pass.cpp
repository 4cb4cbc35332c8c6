#include "resolve_pass.h"

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

ResolvePass::ResolvePass(const std::string& fragment_source, const std::string& name)
    : program_(ShaderProgram::graphics(full_screen_vertex(), fragment_source, name)) {
  glCreateVertexArrays(1, &vertex_array_);
}

ResolvePass::~ResolvePass() {
  if (made_on_.current()) glDeleteVertexArrays(1, &vertex_array_);  // not another context's (gl_context.h)
}

std::pair<double, double> ResolvePass::run(Extent screen, glm::vec3 background, unsigned background_texture,
                                           ClockMode clock) {
  return draw(screen, background, background_texture, false, clock);
}

std::pair<double, double> ResolvePass::run_over(Extent screen, ClockMode clock) {
  return draw(screen, glm::vec3(0.0f), 0, true, clock);
}

std::pair<double, double> ResolvePass::draw(Extent screen, glm::vec3 background, unsigned background_texture,
                                            bool over, ClockMode clock) {
  GlStateGuard::prepare_full_screen_pass();
  if (over) {
    // Over a zero background the composite is the premultiplied (C, 1 - T).
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBlendEquationSeparatei(0, GL_FUNC_ADD, GL_FUNC_ADD);
  }
  glBindVertexArray(vertex_array_);
  glUseProgram(program_.id());
  program_.set("ha_background", background.x, background.y, background.z);
  program_.set("ha_background_from_image", background_texture != 0 ? 1u : 0u);
  // Texture unit 0 is the host's: keep its binding and the active unit.
  GLint active = 0, unit0 = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0);
  if (background_texture != 0) glBindTextureUnit(0, background_texture);
  GlStateGuard::set_viewport(static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  PassClock pass_clock(timer_, clock);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const auto times = pass_clock.stop();
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(unit0));
  glActiveTexture(static_cast<GLenum>(active));
  return times;
}

}  // namespace habuffer::gl
