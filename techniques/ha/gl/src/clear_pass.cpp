#include "clear_pass.h"

#include <algorithm>

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/techniques/ha/gl_ha_table.h"

namespace habuffer::gl {
namespace {

// Whether the host has an occlusion query active: GL keeps one per target,
// and a pass of ours under it would end it or add to its count.
bool host_occlusion_query_active() {
  for (GLenum target : {GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED_CONSERVATIVE}) {
    GLint active = 0;
    glGetQueryiv(target, GL_CURRENT_QUERY, &active);
    if (active != 0) return true;
  }
  return false;
}

}  // namespace

ClearPass::ClearPass(AtomicMode mode, const GlBindings& bindings)
    : program_(ShaderProgram::graphics(full_screen_vertex(), clear_pass_fragment(mode, bindings), "clear pass")) {
  glCreateFramebuffers(1, &framebuffer_);
  glCreateVertexArrays(1, &vertex_array_);
  glCreateQueries(GL_SAMPLES_PASSED, 1, &query_);
  atomic_count_ = GlStorage(sizeof(GLuint64));
  stream_point_ = bindings.stream;
}

ClearPass::~ClearPass() {
  if (!made_on_.current()) return;  // not another context's names (gl_context.h)
  glDeleteQueries(1, &query_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteFramebuffers(1, &framebuffer_);
}

ClearPass::Result ClearPass::run(Extent table, std::uint32_t tile, bool writes, ClockMode clock, unsigned result_buffer,
                                 bool count) {
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
  // The tile loop below steps by tw and th: a limit queried as 0 would never end it.
  if (tw == 0 || th == 0)
    throw GlError("the clear pass's tiles are " + std::to_string(tw) + "x" + std::to_string(th) +
                  " (GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT and GL_MAX_VIEWPORT_DIMS read " + std::to_string(max_w) + ", " +
                  std::to_string(max_h) + ", " + std::to_string(viewport[0]) + "x" + std::to_string(viewport[1]) +
                  "; table " + table.str() + ")");
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(tw));
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(th));
  GlStateGuard::prepare_full_screen_pass();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glBindVertexArray(vertex_array_);
  glUseProgram(program_.id());
  program_.set("ha_clear_writes", writes ? 1u : 0u);
  const bool atomic = host_occlusion_query_active();
  program_.set("ha_clear_atomic_count", atomic ? 1u : 0u);
  PassClock pass_clock(timer_, clock);
  if (atomic) {
    atomic_count_.zero();
    bind_at(GL_SHADER_STORAGE_BUFFER, stream_point_, atomic_count_.id());  // the caller's guard restores the point
  } else if (count) {
    glBeginQuery(GL_SAMPLES_PASSED, query_);
  }
  for (std::uint32_t y = 0; y < table.y; y += th) {
    for (std::uint32_t x = 0; x < table.x; x += tw) {
      program_.set("ha_tile_origin", x, y);
      GlStateGuard::set_viewport(static_cast<GLsizei>(std::min(tw, table.x - x)), static_cast<GLsizei>(std::min(th, table.y - y)));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  if (!atomic && count) glEndQuery(GL_SAMPLES_PASSED);
  // Later passes and read-backs see the zeroed slots (and the atomic count).
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  std::uint64_t stored = 0;
  if (count && atomic) {
    // Tables have at most 2^32 - 1 slots: the low word holds the count, the high word stays 0.
    if (result_buffer != 0)
      glCopyNamedBufferSubData(atomic_count_.id(), result_buffer, 0, 0, sizeof(GLuint64));
    else
      glGetNamedBufferSubData(atomic_count_.id(), 0, sizeof stored, &stored);
  } else if (count && result_buffer != 0) {
    // The GPU writes the result when it has it; nobody waits (the caller's
    // guard restores the host's query-buffer binding).
    glBindBuffer(GL_QUERY_BUFFER, result_buffer);
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, nullptr);
    glBindBuffer(GL_QUERY_BUFFER, 0);
  } else if (count) {
    stored = query_result(query_);
  }
  const auto [wall, gpu] = pass_clock.stop();
  return {stored, wall, gpu};
}

}  // namespace habuffer::gl
