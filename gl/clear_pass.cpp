#include "clear_pass.h"

#include <algorithm>

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

ClearPass::ClearPass(AtomicMode mode, const GlBindings& bindings)
    : program_(ShaderProgram::graphics(full_screen_vertex(), clear_pass_fragment(mode, bindings), "clear pass")) {
  glCreateFramebuffers(1, &framebuffer_);
  glCreateVertexArrays(1, &vertex_array_);
  glCreateQueries(GL_SAMPLES_PASSED, 1, &query_);
}

ClearPass::~ClearPass() {
  glDeleteQueries(1, &query_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteFramebuffers(1, &framebuffer_);
}

ClearPass::Result ClearPass::run(Extent table, std::uint32_t tile, bool writes, bool finish, unsigned result_buffer) {
  GLint max_w = 0, max_h = 0, viewport[2] = {};
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  std::uint32_t tw = std::min<std::uint32_t>({static_cast<std::uint32_t>(max_w), static_cast<std::uint32_t>(viewport[0]), table.x});
  std::uint32_t th = std::min<std::uint32_t>({static_cast<std::uint32_t>(max_h), static_cast<std::uint32_t>(viewport[1]), table.y});
  if (tile > 0) {
    tw = std::min(tw, tile);
    th = std::min(th, tile);
  }
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(tw));
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(th));
  GlStateGuard::prepare_full_screen_pass();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glBindVertexArray(vertex_array_);
  glUseProgram(program_.id());
  program_.set("ha_clear_writes", writes ? 1u : 0u);
  PassClock clock(timer_);
  glBeginQuery(GL_SAMPLES_PASSED, query_);
  for (std::uint32_t y = 0; y < table.y; y += th) {
    for (std::uint32_t x = 0; x < table.x; x += tw) {
      program_.set("ha_tile_origin", x, y);
      GlStateGuard::set_viewport(static_cast<GLsizei>(std::min(tw, table.x - x)), static_cast<GLsizei>(std::min(th, table.y - y)));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glEndQuery(GL_SAMPLES_PASSED);
  // Later passes and read-backs see the zeroed slots.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  if (result_buffer != 0) {
    // The GPU writes the result when it has it; nobody waits (the caller's
    // guard restores the host's query-buffer binding).
    glBindBuffer(GL_QUERY_BUFFER, result_buffer);
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, nullptr);
    glBindBuffer(GL_QUERY_BUFFER, 0);
  }
  const auto [wall, gpu] = clock.stop(finish);
  return {result_buffer != 0 ? 0 : query_result(query_), wall, gpu};
}

}  // namespace habuffer::gl
