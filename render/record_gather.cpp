#include "record_gather.h"

#include <epoxy/gl.h>

#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"

namespace habuffer {

EmptyFramebuffer::EmptyFramebuffer(Extent size) : size_(size) {
  GLuint fb = 0;
  glCreateFramebuffers(1, &fb);
  framebuffer_ = fb;
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(size.x));
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(size.y));
}

EmptyFramebuffer::~EmptyFramebuffer() {
  const GLuint fb = framebuffer_;
  glDeleteFramebuffers(1, &fb);
}

void EmptyFramebuffer::draw_with(const gl::ShaderProgram& program, const std::function<void()>& draw) const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, static_cast<GLsizei>(size_.x), static_cast<GLsizei>(size_.y));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // both facings: entries and exits
  glDisable(GL_BLEND);
  glUseProgram(program.id());
  draw();
  glUseProgram(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

RecordGather gather_records(const BufferConfig& config, gl::AtomicMode mode, bool cpu, std::uint32_t threads,
                            const GatherPass& pass) {
  gl::GlFrameOptions options;
  options.max_attempts = cpu ? 1 : 16;  // lossless: a gather that drops a record is redone larger
  options.capture = options.capture_only = cpu;  // the CPU path: rasterize and capture only
  gl::GlHaBuffer lists(config, OffsetSource{}, mode, options);
  const gl::ShaderProgram program = gl::ShaderProgram::graphics(
      pass.vertex_source, lists.module_source(gl::ShaderStage::Fragment) + pass.fragment_source, pass.name.c_str());
  pass.prepare(program);
  const gl::FrameReport report = lists.frame([&] { pass.draw(program); });
  RecordGather g;
  g.counters = report.counters;
  g.attempts = static_cast<std::uint32_t>(report.attempts.size());
  g.list_bytes = lists.technique().memory_bytes();
  g.table = lists.table();
  if (cpu) {
    InsertOptions insert;
    insert.threads = threads;
    TechniqueBuild b =
        build_technique(ha_technique_config(config), OffsetSource{}, lists.read_capture(), insert, ResizePolicy{}, 16);
    g.counters = b.counters;
    g.attempts = static_cast<std::uint32_t>(b.attempts.size());
    g.buffer = std::move(b.buffer);
    g.table = g.buffer->technique_config().buffer.table;
    g.list_bytes = memory_model_bytes(*g.buffer);
    return g;
  }
  g.buffer = lists.technique().read_back();
  return g;
}

}  // namespace habuffer
