#include "record_gather.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <optional>

#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/lossless_build.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/memory_model.h"
#include "gpu_triangles.h"

namespace habuffer {

void check_screen_fits(Extent screen, const std::string& what) {
  GLint viewport[2] = {}, width = 0, height = 0, texture = 0, renderbuffer = 0;
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &width);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &height);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  struct Limit {
    const char *kind, *names;
    GLint x, y;
  };
  for (const Limit& l : {Limit{"viewport", "GL_MAX_VIEWPORT_DIMS", viewport[0], viewport[1]},
                         Limit{"framebuffer", "GL_MAX_FRAMEBUFFER_WIDTH, _HEIGHT", width, height},
                         Limit{"texture", "GL_MAX_TEXTURE_SIZE", texture, texture},
                         Limit{"renderbuffer", "GL_MAX_RENDERBUFFER_SIZE", renderbuffer, renderbuffer}})
    if (l.x > 0 && l.y > 0 &&  // 0: not reported (no context), the driver's own errors then
        (screen.x > static_cast<std::uint32_t>(l.x) || screen.y > static_cast<std::uint32_t>(l.y)))
      throw gl::GlError(what + " " + screen.str() + " exceeds this OpenGL's largest " + l.kind + " " +
                        std::to_string(l.x) + "x" + std::to_string(l.y) + " (" + l.names + ")");
}

EmptyFramebuffer::EmptyFramebuffer(Extent size) : size_(size) {
  check_screen_fits(size, "a framebuffer of");
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

RecordGather gather_records(Extent screen, bool cpu, std::uint32_t threads, const GatherPass& pass) {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode)
    throw gl::GlError(pass.name + ": L64 records need 64-bit shader types (GL_ARB_gpu_shader_int64), which this "
                      "OpenGL lacks");
  // The counting pass: the table is sized once from the records drawn, not
  // grown by regathers (at load 0.5; lossless growth covers the rest).
  std::uint64_t counted = 0;
  {
    const gl::ShaderProgram counting =
        gl::ShaderProgram::graphics(pass.vertex_source, kCountingFragment, pass.name + " counting pass");
    pass.prepare(counting);  // uniforms the counting shader lacks are ignored
    counted = count_samples([&] { pass.draw(counting); });
  }
  BufferConfig config;
  config.screen = screen;
  config.layout = Layout::L64;
  config.table = table_for_load(screen, std::max<std::uint64_t>(counted, screen.area()), 0.5);
  gl::GlFrameOptions options;
  options.max_attempts = cpu ? 1 : 16;  // lossless: a gather that drops a record is redone larger
  options.capture = options.capture_only = cpu;  // the CPU path: rasterize and capture only
  gl::GlHaBuffer lists(config, OffsetSource{}, *mode, options);
  const gl::ShaderProgram program = gl::ShaderProgram::graphics(
      pass.vertex_source, lists.module_source(gl::ShaderStage::Fragment) + pass.fragment_source, pass.name + " gather");
  pass.prepare(program);
  const gl::FrameReport report = lists.frame([&] { pass.draw(program); });
  RecordGather g;
  g.counters = report.counters;
  g.attempts = static_cast<std::uint32_t>(report.attempts.size());
  g.list_bytes = lists.technique().memory_bytes();
  g.table = lists.table();
  g.layout = config.record_layout();
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
