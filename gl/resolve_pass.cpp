#include "resolve_pass.h"

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {
namespace {

// Draw buffer 0's colour write mask and blend setup, restored on scope exit
// (its blend enable is the state guard's).
class DrawBufferZeroState {
 public:
  DrawBufferZeroState() {
    glGetBooleani_v(GL_COLOR_WRITEMASK, 0, mask_);
    for (int i = 0; i < 6; ++i) glGetIntegeri_v(kBlendNames[i], 0, &blend_[i]);
  }
  ~DrawBufferZeroState() {
    glColorMaski(0, mask_[0], mask_[1], mask_[2], mask_[3]);
    glBlendFuncSeparatei(0, static_cast<GLenum>(blend_[0]), static_cast<GLenum>(blend_[1]),
                         static_cast<GLenum>(blend_[2]), static_cast<GLenum>(blend_[3]));
    glBlendEquationSeparatei(0, static_cast<GLenum>(blend_[4]), static_cast<GLenum>(blend_[5]));
  }
  DrawBufferZeroState(const DrawBufferZeroState&) = delete;
  DrawBufferZeroState& operator=(const DrawBufferZeroState&) = delete;

 private:
  static constexpr GLenum kBlendNames[6] = {GL_BLEND_SRC_RGB,  GL_BLEND_DST_RGB,       GL_BLEND_SRC_ALPHA,
                                            GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
  GLboolean mask_[4] = {};
  GLint blend_[6] = {};
};

}  // namespace

ResolvePass::ResolvePass(const std::string& fragment_source, const std::string& name)
    : program_(ShaderProgram::graphics(full_screen_vertex(), fragment_source, name)) {
  glCreateVertexArrays(1, &vertex_array_);
}

ResolvePass::~ResolvePass() { glDeleteVertexArrays(1, &vertex_array_); }

std::pair<double, double> ResolvePass::run(Extent screen, glm::vec3 background, unsigned background_texture,
                                           bool finish) {
  return draw(screen, background, background_texture, false, finish);
}

std::pair<double, double> ResolvePass::run_over(Extent screen, bool finish) {
  return draw(screen, glm::vec3(0.0f), 0, true, finish);
}

std::pair<double, double> ResolvePass::draw(Extent screen, glm::vec3 background, unsigned background_texture,
                                            bool over, bool finish) {
  const DrawBufferZeroState draw_buffer_zero;
  GlStateGuard::prepare_full_screen_pass();
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
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
  PassClock clock(timer_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const auto times = clock.stop(finish);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(unit0));
  glActiveTexture(static_cast<GLenum>(active));
  return times;
}

}  // namespace habuffer::gl
