#include "gl_state_guard.h"

namespace habuffer::gl {
namespace {

GLint limit(GLenum name) {
  GLint v = 0;
  glGetIntegerv(name, &v);
  return v;
}

// Every capability a pass switches off, with the index GL keeps it per.
std::vector<std::pair<GLenum, GLint>> pass_capabilities() {
  std::vector<std::pair<GLenum, GLint>> caps{
      {GL_DEPTH_TEST, -1},       {GL_STENCIL_TEST, -1},     {GL_CULL_FACE, -1},
      {GL_RASTERIZER_DISCARD, -1}, {GL_COLOR_LOGIC_OP, -1}, {GL_PROGRAM_POINT_SIZE, -1},
      // A multisampled host's coverage state: our passes write every sample
      // (resolve_over must not follow the host's alpha-to-coverage or mask).
      {GL_SAMPLE_ALPHA_TO_COVERAGE, -1}, {GL_SAMPLE_ALPHA_TO_ONE, -1}, {GL_SAMPLE_COVERAGE, -1},
      {GL_SAMPLE_MASK, -1}, {GL_SAMPLE_SHADING, -1}};
  for (GLint i = 0; i < limit(GL_MAX_DRAW_BUFFERS); ++i) caps.emplace_back(GL_BLEND, i);
  for (GLint i = 0; i < limit(GL_MAX_VIEWPORTS); ++i) caps.emplace_back(GL_SCISSOR_TEST, i);
  for (GLint i = 0; i < limit(GL_MAX_CLIP_DISTANCES); ++i) caps.emplace_back(GL_CLIP_DISTANCE0 + i, -1);
  return caps;
}

// The pixel-store parameters of packing (reads into memory or a buffer).
constexpr GLenum kPackParameters[8] = {GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST,   GL_PACK_ROW_LENGTH,   GL_PACK_IMAGE_HEIGHT,
                                       GL_PACK_SKIP_ROWS,  GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_IMAGES, GL_PACK_ALIGNMENT};

// A draw buffer's blend setup, in the order glBlendFuncSeparatei and
// glBlendEquationSeparatei take it.
constexpr GLenum kBlend[6] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                               GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};

void set_capability(GLenum cap, GLint index, bool enabled) {
  if (index < 0)
    (enabled ? glEnable : glDisable)(cap);
  else
    (enabled ? glEnablei : glDisablei)(cap, static_cast<GLuint>(index));
}

void switch_off_pass_capabilities(bool keep_blend) {
  for (const auto& [cap, index] : pass_capabilities())
    if (!(keep_blend && cap == GL_BLEND)) set_capability(cap, index, false);
}

}  // namespace

void GlStateGuard::prepare_full_screen_pass() {
  switch_off_pass_capabilities(false);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  for (GLint d = 1; d < limit(GL_MAX_DRAW_BUFFERS); ++d)
    glColorMaski(static_cast<GLuint>(d), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glBindBuffer(GL_QUERY_BUFFER, 0);
}

void GlStateGuard::prepare_point_pass() {
  switch_off_pass_capabilities(true);
  glPointSize(1.0f);
}

void GlStateGuard::prepare_pack() {
  for (GLenum p : kPackParameters) glPixelStorei(p, p == GL_PACK_ALIGNMENT ? 4 : 0);
}

void GlStateGuard::set_viewport(GLsizei width, GLsizei height) {
  glViewportIndexedf(0, 0.0f, 0.0f, static_cast<GLfloat>(width), static_cast<GLfloat>(height));
}

GLuint64 query_result(GLuint query) {
  GLint bound = 0;
  glGetIntegerv(GL_QUERY_BUFFER_BINDING, &bound);
  if (bound != 0) glBindBuffer(GL_QUERY_BUFFER, 0);
  GLuint64 v = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &v);
  // Put back: a timer read between two guards (the reset pass's clock)
  // must not leave the next gather without the host's query buffer.
  if (bound != 0) glBindBuffer(GL_QUERY_BUFFER, static_cast<GLuint>(bound));
  return v;
}

GlStateGuard::GlStateGuard(const GlBindings& bindings) {
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_QUERY_BUFFER_BINDING, &query_buffer_);
  glGetFloati_v(GL_VIEWPORT, 0, viewport_);
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);
  glGetFloatv(GL_POINT_SIZE, &point_size_);
  draw_buffers_.resize(static_cast<std::size_t>(limit(GL_MAX_DRAW_BUFFERS)));
  for (GLuint d = 0; d < draw_buffers_.size(); ++d) {
    glGetBooleani_v(GL_COLOR_WRITEMASK, d, draw_buffers_[d].mask);
    for (int i = 0; i < 6; ++i) glGetIntegeri_v(kBlend[i], d, &draw_buffers_[d].blend[i]);
  }
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
  for (std::size_t i = 0; i < pack_.size(); ++i) glGetIntegerv(kPackParameters[i], &pack_[i]);
  for (const auto& [cap, index] : pass_capabilities())
    capabilities_.push_back({cap, index, index < 0 ? glIsEnabled(cap) : glIsEnabledi(cap, static_cast<GLuint>(index))});
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
  glBindBuffer(GL_QUERY_BUFFER, static_cast<GLuint>(query_buffer_));
  glViewportIndexedfv(0, viewport_);
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode_[0]));
  glPointSize(point_size_);
  for (GLuint d = 0; d < draw_buffers_.size(); ++d) {
    const GLboolean* m = draw_buffers_[d].mask;
    const GLint* b = draw_buffers_[d].blend;
    glColorMaski(d, m[0], m[1], m[2], m[3]);
    glBlendFuncSeparatei(d, static_cast<GLenum>(b[0]), static_cast<GLenum>(b[1]), static_cast<GLenum>(b[2]),
                         static_cast<GLenum>(b[3]));
    glBlendEquationSeparatei(d, static_cast<GLenum>(b[4]), static_cast<GLenum>(b[5]));
  }
  for (std::size_t i = 0; i < pack_.size(); ++i) glPixelStorei(kPackParameters[i], pack_[i]);
  for (const Capability& c : capabilities_) set_capability(c.cap, c.index, c.enabled != GL_FALSE);
  // A buffer the library replaced meanwhile (a grown capture, a resized
  // table bound at our points before the guard) no longer exists: GL unbinds
  // a deleted buffer, so its binding comes back as 0.
  const auto existing = [](GLint name) { return name != 0 && glIsBuffer(static_cast<GLuint>(name)) ? static_cast<GLuint>(name) : 0u; };
  for (const IndexedBuffer& b : indexed_) {
    const GLuint buffer = existing(b.buffer);
    if (b.size > 0 && buffer != 0)
      glBindBufferRange(b.target, b.index, buffer, b.start, b.size);
    else
      glBindBufferBase(b.target, b.index, buffer);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, existing(storage_generic_));
  glBindBuffer(GL_UNIFORM_BUFFER, existing(uniform_generic_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, existing(pack_buffer_));
}

}  // namespace habuffer::gl
