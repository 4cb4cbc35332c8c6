#include "resolve_pass.h"

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

ResolvePass::ResolvePass(const std::string& module)
    : program_(ShaderProgram::graphics(std::string("#version 450 core\n") + kFullScreenVertex,
                                       module + kResolveFragment, "resolve pass")) {
  glCreateVertexArrays(1, &vertex_array_);
}

ResolvePass::~ResolvePass() { glDeleteVertexArrays(1, &vertex_array_); }

std::pair<double, double> ResolvePass::run(Extent screen, glm::vec3 background, bool finish) {
  GlStateGuard::prepare_full_screen_pass();
  glBindVertexArray(vertex_array_);
  glUseProgram(program_.id());
  program_.set("ha_background", background.x, background.y, background.z);
  GlStateGuard::set_viewport(static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  PassClock clock(timer_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return clock.stop(finish);
}

}  // namespace habuffer::gl
