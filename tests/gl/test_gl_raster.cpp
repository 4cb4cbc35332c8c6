// The host-shader entry: a host fragment shader built on the GLSL module
// (at host-chosen binding points) rasterizes triangles into the HA-buffer;
// the capture mode records what the rasterizer produced, the CPU path
// replays it into the same table, and the resolve pass composites what the
// CPU path composites.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <chrono>
#include <cmath>

#include "gl_test_support.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer {
namespace {

using test::gl_context;

constexpr const char* kHostVertex = R"(#version 450 core
uniform vec3 u_vertices[18];
uniform uint u_colors[6];
flat out uint v_rgba;
void main() {
  gl_Position = vec4(u_vertices[gl_VertexID], 1.0);
  v_rgba = u_colors[gl_VertexID / 3];
}
)";

constexpr const char* kHostInsertColour = R"(
flat in uint v_rgba;
void main() { ha_insert(uvec2(gl_FragCoord.xy), gl_FragCoord.z, v_rgba); }
)";

constexpr const char* kHostInsertDepth = R"(
flat in uint v_rgba;
void main() { ha_insert(uvec2(gl_FragCoord.xy), gl_FragCoord.z); }
)";

// Six overlapping triangles at different depths: several fragments a pixel.
void draw_scene(const gl::ShaderProgram& program, Extent screen) {
  const float v[18 * 3] = {-0.9f, -0.9f, 0.1f,  0.9f,  -0.8f, 0.5f, 0.0f,  0.9f,  -0.3f,   //
                           -1.0f, 0.2f,  0.7f,  0.8f,  0.9f,  -0.6f, 0.6f, -1.0f, 0.0f,    //
                           -0.5f, -1.0f, -0.2f, 0.3f,  1.0f,  0.2f,  -1.0f, 1.0f, 0.9f,    //
                           -0.2f, -0.6f, 0.4f,  0.7f,  0.1f,  0.4f,  -0.4f, 0.5f, 0.4f,    //
                           -1.0f, -1.0f, 0.6f,  1.0f,  -1.0f, 0.6f,  -1.0f, 1.0f, 0.6f,    //
                           -0.3f, -0.3f, -0.8f, 0.3f,  -0.3f, -0.8f, 0.0f,  0.4f, -0.8f};
  const GLuint colours[6] = {0xff000080u, 0x00ff0060u, 0x0000ffa0u, 0xffff0040u, 0x00ffff30u, 0xffffffffu};
  glProgramUniform3fv(program.id(), glGetUniformLocation(program.id(), "u_vertices"), 18, v);
  glProgramUniform1uiv(program.id(), glGetUniformLocation(program.id(), "u_colors"), 6, colours);
  GLuint framebuffer = 0, vertex_array = 0;
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(screen.x));
  glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(screen.y));
  glCreateVertexArrays(1, &vertex_array);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glBindVertexArray(vertex_array);
  glViewport(0, 0, static_cast<GLsizei>(screen.x), static_cast<GLsizei>(screen.y));
  glUseProgram(program.id());
  glDrawArrays(GL_TRIANGLES, 0, 18);
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vertex_array);
  glDeleteFramebuffers(1, &framebuffer);
}

// SPEC 9 on rasterized fragments: what a host fragment shader inserted equals
// the CPU path's table and max-age table for the captured stream, in every
// runnable mode; the capture regathers once when its first capacity is too
// small, and counts every insert call.
TEST(GlRaster, CapturedRasterStreamReplaysIntoTheSameTableOnTheCpu) {
  gl_context();
  const Extent screen{64, 48};
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info())) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config(screen, {100, 75}, test::layout_of(mode), 8);
    gl::GlFrameOptions o;
    o.capture = true;
    o.capture_capacity = 16;
    gl::GlHaBuffer gpu(c, test::random_offsets(12), mode, o, test::host_bindings());
    const auto program = gl::ShaderProgram::graphics(
        kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + (mode == gl::AtomicMode::Native32 ? kHostInsertDepth : kHostInsertColour),
        "host gather");
    const gl::FrameReport r = gpu.frame([&] { draw_scene(program, screen); });
    EXPECT_EQ(r.capture_regathers, 1u);
    EXPECT_EQ(r.captured, r.counters.fragments);
    const std::vector<Fragment> captured = gpu.read_capture();
    ASSERT_EQ(captured.size(), r.counters.fragments);
    ASSERT_GT(captured.size(), 3 * screen.area() / 2);  // depth complexity above 1.5 on average
    const HaBuffer cpu = test::cpu_twin(gpu, captured);
    EXPECT_EQ(gpu.read_table(), test::table_words(cpu));
    EXPECT_EQ(gpu.read_max_age(), cpu.max_age().ages());
    EXPECT_EQ(r.counters.failures(), 0u);
    EXPECT_EQ(r.counters.stored(), cpu.count_stored());
    EXPECT_GT(cpu.count_stored(), screen.area());
    // Capture off: the same frame, no capture, the same table.
    gl::GlHaBuffer plain(c, test::random_offsets(12), mode, {}, test::host_bindings());
    plain.frame([&] { draw_scene(program, screen); });
    EXPECT_EQ(plain.read_table(), test::table_words(cpu));
    EXPECT_TRUE(plain.read_capture().empty());
  }
}

// The resolve pass composites each pixel as the CPU path does (the same
// float32 operations; compared to 1e-6 since the driver may fuse them).
TEST(GlRaster, ResolvePassCompositesWhatTheCpuPathComposites) {
  gl_context();
  const Extent screen{64, 48};
  const gl::AtomicMode mode = gl::runnable_atomic_modes(gl::query_gl_info()).back();
  if (mode == gl::AtomicMode::Native32) GTEST_SKIP() << "compositing needs colour records (L64)";
  const BufferConfig c = test::config(screen, {100, 75}, Layout::L64, 8);
  gl::GlFrameOptions o;
  o.capture = true;
  gl::GlHaBuffer gpu(c, test::random_offsets(5), mode, o);
  const auto program = gl::ShaderProgram::graphics(kHostVertex, gpu.module_source(gl::ShaderStage::Fragment) + kHostInsertColour,
                                                   "host gather");
  const gl::FrameReport r = gpu.frame([&] { draw_scene(program, screen); });
  ASSERT_EQ(r.counters.failures(), 0u);
  EXPECT_THROW(gpu.resolve({0, 0, 0}), gl::GlError);  // framebuffer 0 of a surfaceless context: nothing to draw to
  const glm::vec3 background{0.25f, 0.5f, 0.75f};
  gl::PassTiming timing;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<glm::vec4> image = test::resolve_to_image(gpu, background, &timing);
  const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(timing.wall_ms, 0.0);
  EXPECT_LE(timing.wall_ms, wall);
  const HaBuffer cpu = test::cpu_twin(gpu, gpu.read_capture());
  const std::vector<glm::vec4> expected = cpu.composite_image(background);
  float worst = 0.0f;
  std::uint64_t covered = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(image[i][k] - expected[i][k]));
    covered += expected[i].a > 0.0f;
  }
  EXPECT_LE(worst, 1e-6f);
  EXPECT_GT(covered, screen.area() / 2);
}

}  // namespace
}  // namespace habuffer
