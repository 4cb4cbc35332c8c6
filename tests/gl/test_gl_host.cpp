// Host-context use: a context made with raw EGL calls, as a host app would,
// not by the library; the library works in it and leaves its state alone.
#include <gtest/gtest.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/host_glsl_files.h"

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

// What the blended baselines change around their gather: the draw buffers'
// blend setup and colour masks, the pixel-pack binding and parameters.
struct BlendedState {
  GLint blends[2][6];
  GLboolean masks[2][4];
  GLboolean blend_enabled[2];
  GLint pack_buffer, pack_alignment, pack_row_length, pack_skip_rows, draw_framebuffer;
  bool operator==(const BlendedState& o) const {
    for (int d = 0; d < 2; ++d)
      if (!std::equal(blends[d], blends[d] + 6, o.blends[d]) || !std::equal(masks[d], masks[d] + 4, o.masks[d]) ||
          blend_enabled[d] != o.blend_enabled[d])
        return false;
    return pack_buffer == o.pack_buffer && pack_alignment == o.pack_alignment && pack_row_length == o.pack_row_length &&
           pack_skip_rows == o.pack_skip_rows && draw_framebuffer == o.draw_framebuffer;
  }
};

BlendedState blended_state() {
  BlendedState s{};
  const GLenum names[6] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                           GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
  for (GLuint d = 0; d < 2; ++d) {
    for (int i = 0; i < 6; ++i) glGetIntegeri_v(names[i], d, &s.blends[d][i]);
    glGetBooleani_v(GL_COLOR_WRITEMASK, d, s.masks[d]);
    s.blend_enabled[d] = glIsEnabledi(GL_BLEND, d);
  }
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s.pack_buffer);
  glGetIntegerv(GL_PACK_ALIGNMENT, &s.pack_alignment);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &s.pack_row_length);
  glGetIntegerv(GL_PACK_SKIP_ROWS, &s.pack_skip_rows);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_framebuffer);
  return s;
}

// wboit and blend bind their framebuffer and blend setup for the gather
// only: the host's blend functions, equations, masks and enables of draw
// buffers 0 and 1, its pixel-pack buffer and pack parameters, and its
// framebuffer are as they were after frames and the resolve (and the host
// state of the other test too); inside the gather the technique's
// framebuffer is bound, as gather_framebuffer() names it.
TEST(GlHost, TheBlendedBaselinesLeaveTheHostsBlendSetupPackStateAndFramebufferAlone) {
  HostContext host;
  GLuint pack = 0, renderbuffer = 0, framebuffer = 0;
  glCreateBuffers(1, &pack);
  glNamedBufferData(pack, 64, nullptr, GL_STREAM_READ);
  glCreateRenderbuffers(1, &renderbuffer);
  glNamedRenderbufferStorage(renderbuffer, GL_RGBA8, 20, 14);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glBlendFuncSeparatei(0, GL_DST_COLOR, GL_SRC_COLOR, GL_ONE, GL_ZERO);
  glBlendFuncSeparatei(1, GL_CONSTANT_COLOR, GL_ONE_MINUS_DST_ALPHA, GL_SRC_ALPHA, GL_DST_ALPHA);
  glBlendEquationSeparatei(0, GL_MAX, GL_FUNC_SUBTRACT);
  glBlendEquationSeparatei(1, GL_FUNC_REVERSE_SUBTRACT, GL_MIN);
  glColorMaski(0, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
  glColorMaski(1, GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDisablei(GL_BLEND, 0);
  glEnablei(GL_BLEND, 1);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pack);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 7);
  glPixelStorei(GL_PACK_SKIP_ROWS, 2);
  const BlendedState before = blended_state();
  const HostState host_before = host_state();
  const Extent screen{20, 14};
  for (Technique t : {Technique::Wboit, Technique::Blend}) {
    const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).front();
    TechniqueConfig c = test::technique_config(t, screen, test::layout_of(mode));
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, mode));
    gl::ComputeInserter inserter(gpu);
    const std::vector<Fragment> stream = test::stream(screen, StreamKind::Coherent, 400, 3);
    const gl::FrameReport r = inserter.insert(stream);
    EXPECT_EQ(r.counters.blended, 400u) << to_string(t);
    // The copy ignored the host's pack parameters: the read-back is the CPU's image.
    const auto cpu = make_fragment_buffer(c, OffsetSource{});
    cpu->insert(stream);
    const std::vector<glm::vec3> backgrounds(screen.area(), glm::vec3(0.1f, 0.2f, 0.3f));
    const std::vector<glm::vec4> want = cpu->composite_image(backgrounds);
    const std::vector<glm::vec4> got = gpu.technique().read_back()->composite_image(backgrounds);
    EXPECT_LT(test::largest_difference(got, want), 2e-5f) << to_string(t);
    EXPECT_TRUE(blended_state() == before) << to_string(t);
    EXPECT_TRUE(host_state() == host_before) << to_string(t);
    GLint inside = -1;
    gpu.frame([&] { glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &inside); });
    EXPECT_EQ(static_cast<unsigned>(inside), gpu.technique().gather_framebuffer()) << to_string(t);
    EXPECT_NE(inside, 0) << to_string(t);
    gpu.resolve({0.1f, 0.2f, 0.3f});
    EXPECT_TRUE(blended_state() == before) << to_string(t);
    EXPECT_TRUE(host_state() == host_before) << to_string(t);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(1, &renderbuffer);
  glDeleteBuffers(1, &pack);
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


// Host binding points 0..15, storage and uniform, hold the host's buffers
// inside the gather and after every pass: the library's defaults start at 16.
TEST(GlHost, HostBindingsZeroToFifteenAreNeverTouched) {
  HostContext host;
  constexpr GLuint kPoints = 16;
  GLuint buffers[kPoints];
  glCreateBuffers(kPoints, buffers);
  for (GLuint i = 0; i < kPoints; ++i) {
    glNamedBufferData(buffers[i], 512, nullptr, GL_DYNAMIC_DRAW);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, buffers[i], 0, 256);
    glBindBufferRange(GL_UNIFORM_BUFFER, i, buffers[kPoints - 1 - i], 256, 256);
  }
  const auto bound = [&] {
    std::vector<GLint64> v;
    for (GLuint i = 0; i < kPoints; ++i) {
      GLint b = 0;
      GLint64 start = 0;
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &b);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &start);
      v.insert(v.end(), {b, start});
      glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, i, &b);
      glGetInteger64i_v(GL_UNIFORM_BUFFER_START, i, &start);
      v.insert(v.end(), {b, start});
    }
    return v;
  };
  const std::vector<GLint64> before = bound();
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info())) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config({24, 24}, {30, 30}, test::layout_of(mode), 6);
    gl::GlFrameOptions o;
    o.capture = true;
    gl::GlHaBuffer gpu(c, test::random_offsets(4), mode, o);
    for (unsigned p : gpu.bindings().storage_points()) EXPECT_GE(p, kPoints);
    EXPECT_GE(gpu.bindings().params, kPoints);
    const auto f = test::stream(c.screen, StreamKind::Coherent, 400, 4);
    gl::ComputeInserter inserter(gpu);
    inserter.upload(f);
    std::vector<GLint64> inside;
    gpu.frame([&] {
      inside = bound();
      inserter.dispatch();
    });
    EXPECT_EQ(inside, before);
    EXPECT_EQ(bound(), before);
    test::resolve_to_image(gpu, {0.2f, 0.3f, 0.4f});
    EXPECT_EQ(bound(), before);
  }
  glDeleteBuffers(kPoints, buffers);
}

// A host's raster gather: three overlapping triangles at depths 0.2, 0.45 and
// 0.7 with translucent colours, into an attachment-less framebuffer.
constexpr const char* kHostVertex = R"(#version 450 core
out vec4 host_colour;
void main() {
  int tri = gl_VertexID / 3, k = gl_VertexID % 3;
  vec2 p = k == 0 ? vec2(-1.0, -1.0) : k == 1 ? vec2(3.0, -1.0) : vec2(-1.0, 3.0);
  p = p * (0.4 + 0.2 * float(tri)) + vec2(0.15 * float(tri), -0.1 * float(tri));
  gl_Position = vec4(p, 2.0 * (0.2 + 0.25 * float(tri)) - 1.0, 1.0);
  host_colour = vec4(tri == 0 ? 0.9 : 0.1, tri == 1 ? 0.8 : 0.2, tri == 2 ? 0.7 : 0.3, 0.4 + 0.15 * float(tri));
}
)";
constexpr const char* kHostDeclarations = R"(layout(std140, binding = 0) uniform HostBlock { vec4 host_tint; };
layout(std430, binding = 1) buffer HostCounts { uint host_count; };
in vec4 host_colour;
layout(location = 0) out vec4 host_output;
vec4 host_shade(vec4 c) { return c; }
)";
constexpr const char* kHostMain = R"(void main() {
  atomicAdd(host_count, 1u);
  ha_insert_here(host_shade(host_colour));
  host_output = vec4(0.0);
}
)";

// The host's own uniform block at binding 0 and storage buffer at binding 1
// (low points, below the library's), which its shaders use and update.
struct HostLowBuffers {
  GLuint ids[2] = {0, 0};
  HostLowBuffers() {
    glCreateBuffers(2, ids);
    for (const GLuint b : ids) glNamedBufferData(b, 16, nullptr, GL_DYNAMIC_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, ids[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, ids[1]);
  }
  ~HostLowBuffers() { glDeleteBuffers(2, ids); }
  HostLowBuffers(const HostLowBuffers&) = delete;
  HostLowBuffers& operator=(const HostLowBuffers&) = delete;
  GLuint operator[](std::size_t i) const { return ids[i]; }
};

// The host's own framebuffer (no attachments: the library's buffers are
// the output) and vertex array, drawing the three triangles.
struct HostRaster {
  GLuint framebuffer = 0, vertex_array = 0;
  HostRaster() {
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, 24);  // tests drawing into it themselves
    glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, 24);
    glCreateVertexArrays(1, &vertex_array);
  }
  ~HostRaster() {
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteVertexArrays(1, &vertex_array);
  }
  HostRaster(const HostRaster&) = delete;
  HostRaster& operator=(const HostRaster&) = delete;
  // One frame of `gpu` drawn into a window of `size`, and its resolved image.
  std::vector<glm::vec4> render(gl::GlFrameDriver& gpu, const gl::ShaderProgram& program, Extent size,
                                gl::FrameReport& report) const {
    glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(size.x));
    glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(size.y));
    report = gpu.frame([&] {
      // The blended baselines draw into their own framebuffer, bound by the driver.
      if (gpu.technique().gather_framebuffer() == 0) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
      glViewport(0, 0, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y));
      glUseProgram(program.id());
      glBindVertexArray(vertex_array);
      glDrawArrays(GL_TRIANGLES, 0, 9);
    });
    return test::resolve_to_image(gpu, {0.1f, 0.2f, 0.3f});
  }
  // The same in the 24x24 window most tests use.
  std::vector<glm::vec4> render(gl::GlFrameDriver& gpu, const gl::ShaderProgram& program, gl::FrameReport& report) const {
    return render(gpu, program, {24, 24}, report);
  }
};

// The HA-buffer's current table; zero for the other techniques.
Extent table_of(const gl::GlTechnique& t) {
  const auto* ha = dynamic_cast<const gl::GlHaTable*>(&t);
  return ha ? ha->table() : Extent{};
}

// The binding names docs/embedding.md lists, written here by hand as a host
// reads them there (not by the library's GlBindings::glsl_defines()).
std::string documented_defines(const gl::GlBindings& b) {
  const std::pair<const char*, unsigned> names[] = {
      {"TABLE", b.table},       {"MAX_AGE", b.max_age}, {"OFFSETS", b.offsets},     {"HEADS", b.heads},
      {"NODES", b.nodes},       {"LINKS", b.links},     {"COUNTS", b.counts},       {"LAYERS", b.layers},
      {"SLOTS", b.slots},       {"OCCUPANCY", b.occupancy}, {"LIMITS", b.limits},   {"ACCUM", b.accum},
      {"REVEALAGE", b.revealage}, {"COUNTERS", b.counters}, {"LOCKS", b.locks},     {"CAPTURE", b.capture},
      {"STREAM", b.stream},     {"DEFERRED", b.deferred}, {"SATURATION", b.saturation}, {"PARAMS", b.params}};
  std::string s;
  for (const auto& [name, point] : names) s += "#define HABUFFER_BINDING_" + std::string(name) + " " + std::to_string(point) + "\n";
  return s;
}

// The module placed after the host's own declarations (its uniform block,
// storage buffer, inputs, outputs and functions), as the runtime assembles
// it and as the installed GLSL files give it (at the host's binding points,
// with only the documented names defined before the file: every technique's
// buffers follow them; the lists' once stayed at the defaults and every
// transparent pixel vanished), compiles and renders what the module placed
// first renders, bit for bit.
TEST(GlHost, TheModuleAfterHostDeclarationsRendersTheSame) {
  HostContext host;
  const HostLowBuffers host_buffers;
  const HostRaster raster;
  const gl::GlBindings bindings = test::host_bindings();  // not the defaults the files carry
  std::map<std::string, std::string> files;
  for (const gl::GlslFile& f : gl::host_glsl_files()) files[f.path] = f.text;
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info()))
    for (Technique t : {Technique::Ha, Technique::Lists, Technique::Arrays, Technique::SortedLists, Technique::KBuffer}) {
      SCOPED_TRACE(gl::to_string(mode) + " " + to_string(t));
      TechniqueConfig c;
      c.technique = t;
      c.buffer = test::config({24, 24}, {64, 64}, test::layout_of(mode), 8);
      c.pool_capacity = 4096;
      gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(5), mode, bindings));
      const std::string first = gpu.module_source(gl::ShaderStage::Fragment) + kHostDeclarations + kHostMain;
      const std::string after = "#version 450 core\n" + gl::module_extensions(mode) + kHostDeclarations +
                                gl::technique_module_body(t, mode, bindings, gl::ShaderStage::Fragment) + kHostMain;
      const std::string dir = gl::to_string(mode) + "/";
      ASSERT_EQ(files.count(dir + to_string(t) + ".frag.glsl"), 1u);
      const std::string from_files = "#version 450 core\n" + files[dir + "extensions.glsl"] + kHostDeclarations +
                                     documented_defines(bindings) + files[dir + to_string(t) + ".frag.glsl"] + kHostMain;
      std::vector<std::vector<glm::vec4>> images;
      std::vector<Counters> counters;
      for (const std::string* fragment : {&first, &after, &from_files}) {
        const auto program = gl::ShaderProgram::graphics(kHostVertex, *fragment, "host gather");
        gl::FrameReport report;
        images.push_back(raster.render(gpu, program, report));
        counters.push_back(report.counters);
      }
      EXPECT_GT(counters[0].stored(), 24u * 24u);  // the triangles overlap
      for (std::size_t i = 1; i < images.size(); ++i) {
        EXPECT_TRUE(counters[i] == counters[0]) << i;
        EXPECT_TRUE(images[i] == images[0]) << i;
      }
    }
  std::uint32_t host_count = 0;
  glGetNamedBufferSubData(host_buffers[1], 0, 4, &host_count);
  EXPECT_GT(host_count, 0u);  // the host's own buffer, written by its own code
}

// A host that defines only another technique's binding name (the
// HA-buffer's TABLE) before an installed lists file gets one #error naming
// the lists' own names, not lists bound elsewhere than the container binds
// them (every fragment vanished so before issue 25); defining the lists'
// own name compiles.
TEST(GlHost, DefiningOnlyAnotherTechniquesBindingNameIsACompileErrorNamingThisTechniquesNames) {
  HostContext host;
  std::string lists;
  for (const gl::GlslFile& f : gl::host_glsl_files())
    if (f.path == "native32/lists.frag.glsl") lists = f.text;
  ASSERT_FALSE(lists.empty());
  const auto fragment = [&](const std::string& defines) {
    return "#version 450 core\n" + defines + lists + "void main() { ha_insert_here(vec4(1.0)); }\n";
  };
  try {
    (void)gl::ShaderProgram::graphics(kHostVertex, fragment("#define HABUFFER_BINDING_TABLE 40\n"), "host gather");
    ADD_FAILURE() << "compiled";
  } catch (const gl::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("HABUFFER_BINDING_HEADS, HABUFFER_BINDING_NODES, HABUFFER_BINDING_LINKS"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW((void)gl::ShaderProgram::graphics(
      kHostVertex, fragment("#define HABUFFER_BINDING_TABLE 40\n#define HABUFFER_BINDING_HEADS 41\n"), "host gather"));
}

// Each technique's module declares its own buffers at binding names of its
// own (the k-buffer's occupancy map at OCCUPANCY, not at the HA-buffer's
// MAX_AGE) beside the shared ones: no buffer under another technique's name.
TEST(GlHost, EachTechniquesBuffersAreDeclaredAtBindingNamesOfItsOwn) {
  HostContext host;
  const std::set<std::string> shared = {"COUNTERS", "LOCKS", "CAPTURE", "STREAM", "DEFERRED", "SATURATION", "PARAMS"};
  const std::map<Technique, std::set<std::string>> own = {
      {Technique::Ha, {"TABLE", "MAX_AGE", "OFFSETS"}},       {Technique::Lists, {"HEADS", "NODES", "LINKS"}},
      {Technique::SortedLists, {"HEADS", "NODES", "LINKS"}},  {Technique::PagedLists, {"HEADS", "NODES", "LINKS"}},
      {Technique::Arrays, {"COUNTS", "LAYERS"}},              {Technique::KBuffer, {"SLOTS", "OCCUPANCY", "LIMITS"}},
      {Technique::Wboit, {"ACCUM", "REVEALAGE"}},             {Technique::Blend, {"ACCUM", "REVEALAGE"}}};
  ASSERT_EQ(own.size(), kTechniqueCount);
  const gl::GlBindings bindings = test::host_bindings();
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info()))
    for (const auto& [t, names] : own) {
      SCOPED_TRACE(gl::to_string(mode) + " " + to_string(t));
      std::string module = gl::technique_module_body(t, mode, bindings, gl::ShaderStage::Fragment);
      // The prelude's records take the technique's own name.
      const std::string records = "#define HABUFFER_RECORDS_BINDING HABUFFER_BINDING_";
      if (const auto at = module.find(records); at != std::string::npos)
        module += "binding = HABUFFER_BINDING_" + module.substr(at + records.size(), module.find('\n', at) - at - records.size()) + ")";
      std::set<std::string> declared;
      const std::string key = "binding = HABUFFER_BINDING_";
      for (auto at = module.find(key); at != std::string::npos; at = module.find(key, at + 1)) {
        const auto begin = at + key.size();
        declared.insert(module.substr(begin, module.find(')', begin) - begin));
      }
      std::set<std::string> mine;
      for (const std::string& name : declared)
        if (!shared.count(name)) mine.insert(name);
      EXPECT_EQ(mine, names);
    }
}

// The host's framebuffer has a second colour attachment, an R32UI id buffer
// drawn as draw buffer 1: resolve_over() and resolve() write draw buffer 0
// only and leave every id as it was, and draw buffer 1's mask (on) comes back.
TEST(GlHost, TheResolveLeavesTheHostsIdAttachmentUntouched) {
  HostContext host;
  const Extent screen{24, 24};
  GLuint textures[2], framebuffer = 0;
  glCreateTextures(GL_TEXTURE_2D, 2, textures);
  glTextureStorage2D(textures[0], 1, GL_RGBA32F, 24, 24);
  glTextureStorage2D(textures[1], 1, GL_R32UI, 24, 24);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, textures[0], 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, textures[1], 0);
  const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer, 2, draw_buffers);
  std::vector<std::uint32_t> ids(screen.area());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = 1000u + 7u * static_cast<std::uint32_t>(i);
  glTextureSubImage2D(textures[1], 0, 0, 0, 24, 24, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  gl::GlHaBuffer gpu(test::config(screen, {30, 30}, test::layout_of(mode), 8), test::random_offsets(6), mode);
  gl::ComputeInserter(gpu).insert(test::stream(screen, StreamKind::Random, 2000, 6));  // every pixel, most of them
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  gpu.resolve_over();
  gpu.resolve({0.5f, 0.5f, 0.5f});
  std::vector<std::uint32_t> after(screen.area());
  glGetTextureImage(textures[1], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(after.size() * 4), after.data());
  EXPECT_EQ(static_cast<std::size_t>(std::mismatch(ids.begin(), ids.end(), after.begin()).first - ids.begin()), ids.size())
      << "an id changed";
  GLboolean mask[4] = {};
  glGetBooleani_v(GL_COLOR_WRITEMASK, 1, mask);
  EXPECT_TRUE(mask[0] == GL_TRUE && mask[1] == GL_TRUE && mask[2] == GL_TRUE && mask[3] == GL_TRUE);
  std::vector<glm::vec4> colour(screen.area());
  glGetTextureImage(textures[0], 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(colour.size() * sizeof(glm::vec4)),
                    colour.data());
  EXPECT_TRUE(colour == test::resolve_to_image(gpu, {0.5f, 0.5f, 0.5f})) << "draw buffer 0 holds the resolve";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(2, textures);
}

// Host queries: a GL_TIME_ELAPSED and a GL_SAMPLES_PASSED query of the host
// around frame() (with the clear pass running), the first around the resolve too, keep
// running, end without a GL error, and the samples count only the host's own
// gather; the same two queries inside the gather callback work; the clear
// pass counts the stored records under the host's query as without it.
TEST(GlHost, HostQueriesAroundAndInsideAFrameAreNeverDisturbed) {
  HostContext host;
  const HostLowBuffers host_buffers;
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  gl::GlHaBuffer gpu(test::config({24, 24}, {64, 64}, test::layout_of(mode), 8), test::random_offsets(5), mode);
  const auto program = gl::ShaderProgram::graphics(
      kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kHostDeclarations + kHostMain, "host gather");
  GLuint queries[4];
  glCreateQueries(GL_TIME_ELAPSED, 1, &queries[0]);
  glCreateQueries(GL_SAMPLES_PASSED, 1, &queries[1]);
  glCreateQueries(GL_TIME_ELAPSED, 1, &queries[2]);
  glCreateQueries(GL_SAMPLES_PASSED, 1, &queries[3]);
  const auto draw = [&] {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, raster.framebuffer);
    glViewport(0, 0, 24, 24);
    glUseProgram(program.id());
    glBindVertexArray(raster.vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 9);
  };
  const auto result = [](GLuint q) {
    GLuint64 v = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &v);
    return v;
  };
  while (glGetError() != GL_NO_ERROR) {
  }
  const gl::FrameReport first = gpu.frame(draw);
  ASSERT_EQ(first.counters.failures(), 0u);
  // Around the second frame, whose clear pass counts the first frame's records.
  glBeginQuery(GL_TIME_ELAPSED, queries[0]);
  glBeginQuery(GL_SAMPLES_PASSED, queries[1]);
  const gl::FrameReport second = gpu.frame(draw);
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint texture = 0, framebuffer = 0;  // the host's image, for the resolve under its timer
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA8, 24, 24);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  gpu.resolve_over();
  glEndQuery(GL_TIME_ELAPSED);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &texture);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_TRUE(second.cleared);
  EXPECT_EQ(result(queries[1]), second.counters.fragments) << "the host's samples are its gather's fragments";
  EXPECT_GT(result(queries[0]), 0u);
  // Inside the gather callback.
  const gl::FrameReport third = gpu.frame([&] {
    glBeginQuery(GL_TIME_ELAPSED, queries[2]);
    glBeginQuery(GL_SAMPLES_PASSED, queries[3]);
    draw();
    glEndQuery(GL_SAMPLES_PASSED);
    glEndQuery(GL_TIME_ELAPSED);
  });
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(result(queries[3]), third.counters.fragments);
  EXPECT_GT(result(queries[2]), 0u);
  const gl::FrameReport fourth = gpu.frame(draw);
  // The clear pass under the host's query (second frame, read in the third)
  // and without one (third frame, read in the fourth) count the same records.
  ASSERT_TRUE(third.counted_stored.has_value());
  ASSERT_TRUE(fourth.counted_stored.has_value());
  EXPECT_EQ(*third.counted_stored, first.counters.stored());
  EXPECT_EQ(*fourth.counted_stored, second.counters.stored());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteQueries(4, queries);
}

// resolve_over composites onto the host's image: C + T * destination in
// colour and 1 - T + T * destination alpha in alpha, pixels with nothing
// stored unchanged bit for bit; resolve writes despite the host's colour
// mask; the host's blend setup and mask of draw buffer 0 come back.
TEST(GlHost, ResolveOverBlendsOntoTheHostsFramebuffer) {
  HostContext host;
  const Extent screen{24, 24};
  GLuint texture = 0, framebuffer = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, 24, 24);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
  std::vector<glm::vec4> opaque(screen.area());
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      opaque[x + y * screen.x] = {float(x) / 24.0f, float(y) / 24.0f, 0.25f, 0.75f};
  const auto upload = [&] {
    glTextureSubImage2D(texture, 0, 0, 0, 24, 24, GL_RGBA, GL_FLOAT, opaque.data());
  };
  const auto read = [&] {
    std::vector<glm::vec4> image(screen.area());
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.size() * sizeof(glm::vec4)),
                      image.data());
    return image;
  };
  glBlendFuncSeparatei(0, GL_SRC_COLOR, GL_DST_COLOR, GL_ZERO, GL_SRC_ALPHA);
  glBlendEquationSeparatei(0, GL_FUNC_SUBTRACT, GL_MAX);
  glColorMaski(0, GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  const BufferConfig c = test::config(screen, {30, 30}, test::layout_of(mode), 8);
  gl::GlHaBuffer gpu(c, test::random_offsets(6), mode);
  const auto f = test::stream(screen, StreamKind::Random, 300, 6);  // leaves many pixels empty
  gl::ComputeInserter(gpu).insert(f);
  const std::vector<glm::vec4> premultiplied = test::resolve_to_image(gpu, glm::vec3(0.0f));  // (C, 1 - T)
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  upload();
  gpu.resolve_over();
  const std::vector<glm::vec4> over = read();
  std::size_t empty = 0;
  for (std::size_t i = 0; i < over.size(); ++i) {
    const glm::vec4 s = premultiplied[i], d = opaque[i];
    if (s == glm::vec4(0.0f)) {
      ++empty;
      EXPECT_TRUE(over[i] == d) << i;
      continue;
    }
    const glm::vec4 expected = s + (1.0f - s.a) * d;
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(over[i][k], expected[k], 1e-6f) << i << " " << k;
  }
  EXPECT_GT(empty, 0u);
  EXPECT_LT(empty, over.size());
  // The replacing resolve writes despite the host's mask, and its alpha is 1 - T.
  upload();
  gpu.resolve({0.5f, 0.5f, 0.5f});
  const std::vector<glm::vec4> replaced = read();
  for (std::size_t i = 0; i < replaced.size(); ++i) {
    EXPECT_NEAR(replaced[i].a, premultiplied[i].a, 1e-7f) << i;
    EXPECT_NEAR(replaced[i].r, premultiplied[i].r + (1.0f - premultiplied[i].a) * 0.5f, 1e-6f) << i;
  }
  GLint blend[6] = {};
  const GLenum names[6] = {GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA,
                           GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
  for (int i = 0; i < 6; ++i) glGetIntegeri_v(names[i], 0, &blend[i]);
  EXPECT_EQ(blend[0], GL_SRC_COLOR);
  EXPECT_EQ(blend[1], GL_DST_COLOR);
  EXPECT_EQ(blend[2], GL_ZERO);
  EXPECT_EQ(blend[3], GL_SRC_ALPHA);
  EXPECT_EQ(blend[4], GL_FUNC_SUBTRACT);
  EXPECT_EQ(blend[5], GL_MAX);
  GLboolean mask[4] = {};
  glGetBooleani_v(GL_COLOR_WRITEMASK, 0, mask);
  EXPECT_TRUE(mask[0] == GL_FALSE && mask[1] == GL_TRUE && mask[2] == GL_FALSE && mask[3] == GL_FALSE);
  EXPECT_FALSE(glIsEnabledi(GL_BLEND, 0));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &texture);
}

// pool_capacity 0 on the GPU is the automatic pool: one node per pixel at
// first, the first frame (three overlapping triangles: more fragments than
// pixels) is counted before its gather and the pool (or the HA-buffer's
// table) sized from the count by SPEC 8's rule, so nothing drops and one
// gather suffices, without lossless mode, and renders the HA-buffer's
// image; the next frame runs no counting gather and fits in one attempt.
TEST(GlHost, AnAutomaticContainerIsSizedFromACountingGatherBeforeItsFirstFrame) {
  HostContext host;
  const HostLowBuffers host_buffers;
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  std::vector<std::vector<glm::vec4>> images;
  for (Technique t : {Technique::Ha, Technique::Lists, Technique::SortedLists}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c;
    c.technique = t;
    c.buffer = test::config({24, 24}, {}, test::layout_of(mode), 8);  // the HA-buffer's table automatic
    c.pool_capacity = 0;  // the default: automatic
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(5), mode));
    const auto program = gl::ShaderProgram::graphics(
        kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kHostDeclarations + kHostMain, "host gather");
    gl::FrameReport report;
    ASSERT_TRUE(gpu.counts_next_frame());
    images.push_back(raster.render(gpu, program, report));
    EXPECT_FALSE(gpu.counts_next_frame());
    EXPECT_EQ(report.counters.failures(), 0u);
    ASSERT_TRUE(report.counted_fragments.has_value());
    EXPECT_EQ(*report.counted_fragments, report.counters.fragments);  // every call on the screen
    EXPECT_GT(*report.counted_fragments, 24u * 24u);                  // more than the screen holds
    EXPECT_EQ(report.attempts.size(), 1u);
    const ResizePolicy policy;
    if (t == Technique::Ha)
      EXPECT_EQ(table_of(gpu.technique()), policy.initial_table({24, 24}, *report.counted_fragments));
    else
      EXPECT_EQ(report.attempts.front().capacity, policy.automatic(*report.counted_fragments));
    EXPECT_TRUE(images.back() == images.front());
    (void)raster.render(gpu, program, report);
    EXPECT_FALSE(report.counted_fragments.has_value());
    EXPECT_EQ(report.attempts.size(), 1u);
    EXPECT_EQ(report.counters.failures(), 0u);
  }
}

// A host whose window grew beyond the container's screen (the triangles
// drawn at 24x24 into a 16x16 container, as after a resize without a new
// container): the fragments beyond the screen are lost, counted invalid and
// off_screen, and the frame is not lossless; at the right size it is.
TEST(GlHost, FragmentsBeyondTheScreenAreALossTheReportSays) {
  HostContext host;
  const HostLowBuffers host_buffers;
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  for (const Extent screen : {Extent{16, 16}, Extent{24, 24}}) {
    SCOPED_TRACE(screen.str());
    gl::GlHaBuffer gpu(test::config(screen, {64, 64}, test::layout_of(mode), 8), test::random_offsets(5), mode);
    const auto program = gl::ShaderProgram::graphics(
        kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kHostDeclarations + kHostMain, "host gather");
    gl::FrameReport report;
    (void)raster.render(gpu, program, report);
    EXPECT_EQ(report.counters.failures(), 0u);
    EXPECT_EQ(report.off_screen, report.counters.invalid);
    if (screen.x < 24) {
      EXPECT_GT(report.off_screen, 0u);
      EXPECT_FALSE(report.lossless());
    } else {
      EXPECT_EQ(report.off_screen, 0u);
      EXPECT_TRUE(report.lossless());
    }
  }
}

// The same triangles drawn by a reversed-Z host (glClipControl zero-to-one,
// window depth 1 nearest): depth 1 - d where kHostVertex gives d.
constexpr const char* kHostVertexReversed = R"(#version 450 core
out vec4 host_colour;
void main() {
  int tri = gl_VertexID / 3, k = gl_VertexID % 3;
  vec2 p = k == 0 ? vec2(-1.0, -1.0) : k == 1 ? vec2(3.0, -1.0) : vec2(-1.0, 3.0);
  p = p * (0.4 + 0.2 * float(tri)) + vec2(0.15 * float(tri), -0.1 * float(tri));
  gl_Position = vec4(p, 1.0 - (0.2 + 0.25 * float(tri)), 1.0);
  host_colour = vec4(tri == 0 ? 0.9 : 0.1, tri == 1 ? 0.8 : 0.2, tri == 2 ? 0.7 : 0.3, 0.4 + 0.15 * float(tri));
}
)";

// A reversed-Z host (glClipControl zero-to-one, GL_GREATER) with
// DepthConvention::Reversed renders the standard host's image; with the
// default convention its GL_GREATER depth test is refused in one line
// instead of compositing back to front (which would give another image).
TEST(GlHost, AReversedZHostRendersTheStandardImageWithTheReversedConvention) {
  HostContext host;
  const HostLowBuffers host_buffers;
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  TechniqueConfig c;
  c.buffer = test::config({24, 24}, {64, 64}, test::layout_of(mode), 8);
  const auto image = [&](const char* vertex, gl::DepthConvention convention) {
    gl::GlFrameOptions o;
    o.depth = convention;
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(5), mode), o);
    const auto program = gl::ShaderProgram::graphics(
        vertex, gpu.module_source(gl::ShaderStage::Fragment) + kHostDeclarations + kHostMain, "host gather");
    gl::FrameReport report;
    auto out = raster.render(gpu, program, report);
    EXPECT_EQ(report.counters.failures(), 0u);
    return out;
  };
  const std::vector<glm::vec4> standard = image(kHostVertex, gl::DepthConvention::Standard);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);  // no depth attachment in the gather: every fragment passes
  glDepthFunc(GL_GREATER);
  EXPECT_TRUE(image(kHostVertexReversed, gl::DepthConvention::Reversed) == standard);
  try {
    (void)image(kHostVertexReversed, gl::DepthConvention::Standard);
    ADD_FAILURE() << "a GL_GREATER depth test was taken for the standard convention";
  } catch (const gl::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("GL_GREATER (reversed-Z) but GlFrameOptions::depth is Standard"),
              std::string::npos)
        << e.what();
  }
  glDisable(GL_DEPTH_TEST);  // what the check cannot see: the lists come out back to front
  EXPECT_FALSE(image(kHostVertexReversed, gl::DepthConvention::Standard) == standard);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
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

namespace habuffer {
namespace {

// A host's raster gather at any window size: kHostVertex's triangles over
// the viewport (0, 0, size), drawn by a shader that only inserts (no colour
// output of its own, so the blended baselines' outputs are the module's).
constexpr const char* kResizeMain = R"(in vec4 host_colour;
void main() { ha_insert_here(host_colour); }
)";


// Every GL technique at 16x16 (the HA-buffer with its automatic table and
// with an explicit one, the lists with the automatic pool, K 4 of the
// three triangles), then resized in place to a larger and a smaller window:
// the host calls one method, resize_screen, with its state untouched; the
// next frame covers the whole new window (nothing off the screen, nothing
// lost) and renders bit for bit, with the same lists, what a container made
// fresh at that size renders; the memory counter is a fresh container's of
// the same capacity; the automatic table becomes the new screen, an explicit
// one keeps its ratio to the screen.
TEST(GlHost, EveryTechniqueResizedInPlaceRendersWhatAFreshContainerOfTheNewScreenRenders) {
  HostContext host;
  GLuint host_buffer = 0;
  glCreateBuffers(1, &host_buffer);
  glNamedBufferData(host_buffer, 16, nullptr, GL_DYNAMIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, host_buffer);
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  const Extent a{16, 16};
  gl::GlFrameOptions lossless;  // the HA-buffer's table grows in the first frame
  lossless.max_attempts = 8;
  struct Case {
    Technique technique;
    Extent table;  // the HA-buffer's; zero: automatic
  };
  for (const Case k : {Case{Technique::Ha, {}}, Case{Technique::Ha, {20, 20}}, Case{Technique::Lists, {}},
                       Case{Technique::SortedLists, {}}, Case{Technique::Arrays, {}}, Case{Technique::KBuffer, {}},
                       Case{Technique::Wboit, {}}, Case{Technique::Blend, {}}}) {
    SCOPED_TRACE(to_string(k.technique) + " table " + k.table.str());
    TechniqueConfig c;
    c.technique = k.technique;
    c.buffer = test::config(a, k.table, test::layout_of(mode), 8);
    c.layers = 4;
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(5), mode), lossless);
    const auto program = gl::ShaderProgram::graphics(
        kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kResizeMain, "host gather");
    gl::FrameReport report;
    (void)raster.render(gpu, program, a, report);
    ASSERT_TRUE(report.lossless());
    Extent table = table_of(gpu.technique());
    for (const Extent s : {Extent{24, 20}, Extent{12, 10}}) {
      SCOPED_TRACE("resized to " + s.str());
      const Extent old = gpu.screen();
      const HostState before = host_state();
      gpu.resize_screen(s);
      EXPECT_TRUE(host_state() == before);
      EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      ASSERT_EQ(gpu.screen(), s);
      TechniqueConfig fresh_config = c;
      fresh_config.buffer.screen = s;
      if (k.technique == Technique::Ha) {
        // Each side scaled by the screen's, rounded up; offsets for it.
        const Extent expected{(table.x * s.x + old.x - 1) / old.x, (table.y * s.y + old.y - 1) / old.y};
        EXPECT_EQ(table_of(gpu.technique()), expected);
        EXPECT_EQ(static_cast<gl::GlHaTable&>(gpu.technique()).offsets().table(), expected);
        table = table_of(gpu.technique());
        fresh_config.buffer.table = table;
        if (k.table.area() == 0) {
          // An automatic table no frame grew becomes the new screen, as in a fresh container.
          gl::GlFrameDriver unused(gl::make_gl_technique(c, test::random_offsets(5), mode));
          unused.resize_screen(s);
          EXPECT_EQ(table_of(unused.technique()), s);
        }
      }
      {
        // The memory of the same capacity (the scaled pool) made fresh.
        TechniqueConfig same = fresh_config;
        if (uses_pool(k.technique)) same.pool_capacity = gpu.technique().capacity();
        const auto made = gl::make_gl_technique(same, test::random_offsets(5), mode);
        EXPECT_EQ(gpu.technique().memory_bytes(), made->memory_bytes());
        EXPECT_EQ(gpu.technique().capacity(), made->capacity());
      }
      const std::vector<glm::vec4> image = raster.render(gpu, program, s, report);
      // An automatic container counts the new screen's first frame and is sized from it.
      EXPECT_EQ(report.counted_fragments.has_value(), gpu.technique().sized_automatically());
      table = table_of(gpu.technique());
      EXPECT_EQ(report.off_screen, 0u);
      EXPECT_TRUE(report.lossless());
      EXPECT_GT(report.counters.stored() + report.counters.blended, 0u);
      gl::GlFrameDriver fresh(gl::make_gl_technique(fresh_config, test::random_offsets(5), mode), lossless);
      gl::FrameReport fresh_report;
      const std::vector<glm::vec4> expected = raster.render(fresh, program, s, fresh_report);
      ASSERT_TRUE(fresh_report.lossless());
      EXPECT_EQ(report.counters.stored(), fresh_report.counters.stored());
      EXPECT_TRUE(image == expected);
      if (stores_lists(k.technique)) {
        EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()),
                  test::traversed_lists(*fresh.technique().read_back()));
      }
    }
  }
  glDeleteBuffers(1, &host_buffer);
}

// Screens a container cannot take are refused before anything changes: an
// empty one (std::invalid_argument naming it) and one beyond the largest
// viewport or beyond a shader-storage buffer (GlError naming the sizes and
// the limit, as at construction); the container keeps its screen, memory and
// buffers and renders the same image as before at its old size.
TEST(GlHost, ARefusedScreenResizeNamesTheSizesAndLeavesTheContainerWorkingAtItsOldSize) {
  HostContext host;
  const HostRaster raster;
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  const Extent a{16, 16};
  GLint viewport[2] = {};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  const Extent wide{static_cast<std::uint32_t>(viewport[0]) + 1, 16};
  // Within the viewport and 32-bit indices, beyond one shader-storage buffer:
  // more rows of 64 pixels than the largest buffer holds at K 64 and 4 bytes
  // a slot (or 8).
  const std::uint64_t rows = gl::max_storage_bytes() / (4 * 64 * 64) + 1;
  const bool storage_testable = rows <= static_cast<std::uint64_t>(viewport[1]) && rows * 64 * 64 < UINT32_MAX;
  for (Technique t : {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::Arrays, Technique::KBuffer,
                      Technique::Wboit, Technique::Blend}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c;
    c.technique = t;
    c.buffer = test::config(a, {}, test::layout_of(mode), 8);
    c.layers = 4;
    gl::GlFrameOptions lossless;
    lossless.max_attempts = 8;
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(5), mode), lossless);
    const auto program = gl::ShaderProgram::graphics(
        kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kResizeMain, "host gather");
    gl::FrameReport report;
    const std::vector<glm::vec4> before = raster.render(gpu, program, a, report);
    ASSERT_TRUE(report.lossless());
    const std::uint64_t memory = gpu.memory_bytes(), capacity = gpu.technique().capacity();
    const Extent table = table_of(gpu.technique());
    try {
      gpu.resize_screen({0, 16});
      ADD_FAILURE() << "an empty screen was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("0x16"), std::string::npos) << e.what();
    }
    try {
      gpu.resize_screen(wide);
      ADD_FAILURE() << "a screen beyond the viewport was taken";
    } catch (const gl::GlError& e) {
      EXPECT_NE(std::string(e.what()).find(wide.str()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("viewport"), std::string::npos) << e.what();
    }
    if (storage_testable && uses_layers(t)) {
      // K 64 set at construction would not fit either: a container of K 64 at 16x16, resized.
      TechniqueConfig deep = c;
      deep.layers = 64;
      gl::GlFrameDriver d(gl::make_gl_technique(deep, test::random_offsets(5), mode));
      const std::uint64_t deep_memory = d.memory_bytes();
      const Extent tall{64, static_cast<std::uint32_t>(rows)};
      try {
        d.resize_screen(tall);
        ADD_FAILURE() << "a screen beyond a shader-storage buffer was taken";
      } catch (const gl::GlError& e) {
        EXPECT_NE(std::string(e.what()).find(tall.str()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("shader-storage"), std::string::npos) << e.what();
      }
      EXPECT_EQ(d.screen(), a);
      EXPECT_EQ(d.memory_bytes(), deep_memory);
      EXPECT_EQ(d.technique().capacity(), 64u * a.area());
    }  // else a context whose buffers hold any screen of its viewport: nothing to refuse
    EXPECT_EQ(gpu.screen(), a);
    EXPECT_EQ(gpu.memory_bytes(), memory);
    EXPECT_EQ(gpu.technique().capacity(), capacity);
    EXPECT_EQ(table_of(gpu.technique()), table);
    EXPECT_TRUE(raster.render(gpu, program, a, report) == before);
    EXPECT_TRUE(report.lossless());
    EXPECT_EQ(report.off_screen, 0u);
  }
}

}  // namespace
}  // namespace habuffer
