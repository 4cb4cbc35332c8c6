// Host-context use: a context made with raw EGL calls, as a host app would,
// not by the library; the library works in it and leaves its state alone.
#include <gtest/gtest.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "gl_test_support.h"

namespace habuffer {
namespace {

// A headless OpenGL 4.5 core context made current on this thread, with
// Mesa's surfaceless platform (the device platform when that is missing).
class HostContext {
 public:
  HostContext() {
    display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY) {
      EGLDeviceEXT device = nullptr;
      EGLint n = 0;
      if (eglQueryDevicesEXT(1, &device, &n) && n > 0)
        display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    }
    EXPECT_NE(display_, EGL_NO_DISPLAY);
    EXPECT_TRUE(eglInitialize(display_, nullptr, nullptr));
    eglBindAPI(EGL_OPENGL_API);
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    EXPECT_NE(context_, EGL_NO_CONTEXT);
    EXPECT_TRUE(eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_));
  }
  ~HostContext() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  HostContext(const HostContext&) = delete;
  HostContext& operator=(const HostContext&) = delete;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

struct HostState {
  GLint program, vertex_array, draw_framebuffer, viewport[4], polygon_mode[2];
  GLboolean blend, depth, cull, scissor, stencil, discard, blend1, scissor1, clip0;
  GLfloat viewport1[4];
  GLint query_buffer;
  GLint storage[7], storage_generic, uniform0, uniform_generic;
  GLint64 start2, size2;
  bool operator==(const HostState& o) const {
    return program == o.program && vertex_array == o.vertex_array && draw_framebuffer == o.draw_framebuffer &&
           std::equal(viewport, viewport + 4, o.viewport) && polygon_mode[0] == o.polygon_mode[0] &&
           blend == o.blend && depth == o.depth && cull == o.cull && scissor == o.scissor && stencil == o.stencil &&
           discard == o.discard && blend1 == o.blend1 && scissor1 == o.scissor1 && clip0 == o.clip0 &&
           std::equal(viewport1, viewport1 + 4, o.viewport1) && query_buffer == o.query_buffer &&
           std::equal(storage, storage + 7, o.storage) && storage_generic == o.storage_generic &&
           uniform0 == o.uniform0 && uniform_generic == o.uniform_generic && start2 == o.start2 && size2 == o.size2;
  }
};

HostState host_state() {
  HostState s{};
  glGetIntegerv(GL_CURRENT_PROGRAM, &s.program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vertex_array);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_framebuffer);
  glGetIntegerv(GL_VIEWPORT, s.viewport);
  glGetIntegerv(GL_POLYGON_MODE, s.polygon_mode);
  s.blend = glIsEnabled(GL_BLEND);
  s.depth = glIsEnabled(GL_DEPTH_TEST);
  s.cull = glIsEnabled(GL_CULL_FACE);
  s.scissor = glIsEnabled(GL_SCISSOR_TEST);
  s.stencil = glIsEnabled(GL_STENCIL_TEST);
  s.discard = glIsEnabled(GL_RASTERIZER_DISCARD);
  s.blend1 = glIsEnabledi(GL_BLEND, 1);
  s.scissor1 = glIsEnabledi(GL_SCISSOR_TEST, 1);
  s.clip0 = glIsEnabled(GL_CLIP_DISTANCE0);
  glGetFloati_v(GL_VIEWPORT, 1, s.viewport1);
  glGetIntegerv(GL_QUERY_BUFFER_BINDING, &s.query_buffer);
  for (GLuint i = 0; i < 7; ++i) glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &s.storage[i]);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 2, &s.start2);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 2, &s.size2);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.storage_generic);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &s.uniform0);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.uniform_generic);
  return s;
}

// Host-context use: in a context the host made itself, the host's program,
// vertex array, framebuffer, viewport, capabilities, polygon mode and buffer
// bindings at our very binding points are unchanged by frames (gather and
// clear pass), counting and resolve; no debug callback is installed.
TEST(GlHost, EveryPassRestoresTheStateOfTheHostsOwnContext) {
  HostContext host;
  GLuint buffers[2], framebuffer = 0, renderbuffer = 0, vertex_array = 0;
  glCreateBuffers(2, buffers);
  glNamedBufferData(buffers[0], 256, nullptr, GL_STATIC_DRAW);
  glNamedBufferData(buffers[1], 256, nullptr, GL_STATIC_DRAW);
  glCreateRenderbuffers(1, &renderbuffer);
  glNamedRenderbufferStorage(renderbuffer, GL_RGBA8, 24, 24);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer);
  glCreateVertexArrays(1, &vertex_array);
  auto host_program = gl::ShaderProgram::compute("#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n", "host");
  glUseProgram(host_program.id());
  glBindVertexArray(vertex_array);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glViewport(3, 4, 5, 6);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glEnable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glEnable(GL_SCISSOR_TEST);
  glDisablei(GL_SCISSOR_TEST, 1);  // per-viewport state differs between indices
  glEnablei(GL_BLEND, 1);
  glDisablei(GL_BLEND, 0);
  glEnable(GL_STENCIL_TEST);
  glEnable(GL_CLIP_DISTANCE0);
  glViewportIndexedf(1, 7.0f, 8.0f, 9.0f, 10.0f);
  glBindBuffer(GL_QUERY_BUFFER, buffers[1]);  // query results would land in this buffer
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, buffers[0], 64, 128);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[1]);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers[1]);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
  glBindBuffer(GL_UNIFORM_BUFFER, buffers[0]);
  const HostState before = host_state();
  {
    const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
    const BufferConfig c = test::config({24, 24}, {30, 30}, test::layout_of(mode), 6);
    gl::GlFrameOptions o;
    o.adaptive = true;
    o.capture = true;
    gl::GlHaBuffer gpu(c, test::random_offsets(1), mode, o);
    gl::ComputeInserter inserter(gpu);
    const auto f = test::stream(c.screen, StreamKind::Coherent, 500, 1);
    inserter.insert(f);
    EXPECT_TRUE(host_state() == before);
    const gl::FrameReport second = inserter.insert(f);  // with the clear pass, its count into our query buffer
    EXPECT_TRUE(host_state() == before);
    EXPECT_TRUE(second.cleared);
    const gl::FrameReport third = inserter.insert(f);  // reads that count
    EXPECT_TRUE(host_state() == before);
    ASSERT_TRUE(third.counted_stored.has_value());
    EXPECT_EQ(*third.counted_stored, second.counters.stored());  // the query result came back through our buffer
    // The gather runs in the host's state, not the clear pass's.
    HostState seen{};
    gpu.frame([&] { seen = host_state(); });
    EXPECT_EQ(seen.draw_framebuffer, before.draw_framebuffer);
    EXPECT_TRUE(std::equal(seen.viewport, seen.viewport + 4, before.viewport));
    EXPECT_EQ(seen.depth, before.depth);
    EXPECT_EQ(seen.vertex_array, before.vertex_array);
    gpu.count_stored();
    EXPECT_TRUE(host_state() == before);
    gpu.resolve({0.5f, 0.5f, 0.5f});
    EXPECT_TRUE(host_state() == before);
  }
  EXPECT_TRUE(host_state() == before);
  GLvoid* callback = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
  EXPECT_EQ(callback, nullptr);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  for (GLenum cap : {GL_BLEND, GL_DEPTH_TEST, GL_CULL_FACE, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_CLIP_DISTANCE0})
    glDisable(cap);
  glBindBuffer(GL_QUERY_BUFFER, 0);
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vertex_array);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(1, &renderbuffer);
  glDeleteBuffers(2, buffers);
}

// Inside the gather the host's generic GL_UNIFORM_BUFFER and
// GL_SHADER_STORAGE_BUFFER bindings are its own: a host updating "its" UBO
// and SSBO there writes its buffers, never our parameter block or table
// (which would make every fragment invalid, with no error).
TEST(GlHost, TheGatherSeesTheHostsOwnGenericBufferBindings) {
  HostContext host;
  GLuint host_ubo = 0, host_ssbo = 0;
  glCreateBuffers(1, &host_ubo);
  glCreateBuffers(1, &host_ssbo);
  glNamedBufferData(host_ubo, 256, nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(host_ssbo, 256, nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, host_ubo);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, host_ssbo);
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info())) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config({24, 24}, {30, 30}, test::layout_of(mode), 6);
    gl::GlHaBuffer gpu(c, test::random_offsets(2), mode);
    gl::ComputeInserter inserter(gpu);
    const auto f = test::stream(c.screen, StreamKind::Coherent, 500, 3);
    inserter.upload(f);
    const std::vector<std::uint32_t> garbage(64, 0xDEADBEEFu);
    GLint seen_ubo = 0, seen_ssbo = 0;
    const gl::FrameReport r = gpu.frame(
        [&] {
          glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &seen_ubo);
          glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &seen_ssbo);
          glBufferSubData(GL_UNIFORM_BUFFER, 0, 256, garbage.data());
          glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, 256, garbage.data());
          inserter.dispatch();
        },
        [&] { return std::uint64_t{f.size()}; });
    EXPECT_EQ(static_cast<GLuint>(seen_ubo), host_ubo);
    EXPECT_EQ(static_cast<GLuint>(seen_ssbo), host_ssbo);
    std::uint32_t first = 0;
    glGetNamedBufferSubData(host_ubo, 0, 4, &first);
    EXPECT_EQ(first, 0xDEADBEEFu);
    glGetNamedBufferSubData(host_ssbo, 0, 4, &first);
    EXPECT_EQ(first, 0xDEADBEEFu);
    const HaBuffer cpu = test::cpu_twin(gpu, f);
    EXPECT_EQ(r.counters.invalid, 0u);
    EXPECT_EQ(r.counters.stored(), cpu.count_stored());
    EXPECT_EQ(gpu.read_table(), test::table_words(cpu));
  }
  glDeleteBuffers(1, &host_ubo);
  glDeleteBuffers(1, &host_ssbo);
}

}  // namespace
}  // namespace habuffer

namespace habuffer {
namespace {

// render binds our buffers itself before the first frame (its counting
// pass); a capture that grows inside the frame replaces one of them, and the
// frame's state guard must not rebind the deleted name (GL_INVALID_OPERATION).
TEST(GlHost, BuffersReplacedInsideAFrameAreNotRebound) {
  test::gl_context();
  while (glGetError() != GL_NO_ERROR) {
  }
  const Extent screen{16, 16};
  gl::GlFrameOptions o;
  o.capture = true;
  o.capture_capacity = 8;
  const gl::AtomicMode mode = *gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  gl::GlHaBuffer gpu(test::config(screen, {20, 20}), test::random_offsets(1), mode, o, test::host_bindings());
  gpu.bind();
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Random, 200, 3);
  const gl::FrameReport r = gl::ComputeInserter(gpu).insert(frags);
  EXPECT_EQ(r.capture_regathers, 1u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  GLint bound = -1;
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, test::host_bindings().capture, &bound);
  EXPECT_TRUE(bound == 0 || glIsBuffer(static_cast<GLuint>(bound)));
}

}  // namespace
}  // namespace habuffer
