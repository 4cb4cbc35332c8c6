// The GPU path's per-frame machinery (SPEC 8): the clear pass's occlusion
// count, adaptive sizing with one frame of latency, lossless regathering, and
// the GL state a host app set surviving every pass.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <chrono>

#include "gl_test_support.h"
#include "habuffer/lossless_build.h"

namespace habuffer {
namespace {

using test::gl_context;

std::vector<gl::AtomicMode> modes() { return gl::runnable_atomic_modes(gl::query_gl_info()); }

// The occlusion query over the clear pass counts exactly the stored records,
// also when the pass runs in tiles (here forced by a small tile side), and
// the pass leaves every slot empty.
TEST(GlFrame, ClearPassOcclusionCountIsExactAndEmptiesTheTable) {
  gl_context();
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    for (std::uint32_t tile : {0u, 7u, 64u}) {
      SCOPED_TRACE("tile " + std::to_string(tile));
      const BufferConfig c = test::config({50, 30}, {71, 43}, test::layout_of(mode), 8);
      gl::GlFrameOptions o;
      o.clear_tile = tile;
      gl::GlHaBuffer gpu(c, test::random_offsets(4), mode, o);
      gl::ComputeInserter inserter(gpu);
      const auto f = test::stream(c.screen, StreamKind::Coherent, 2400, tile + 1);
      const gl::FrameReport first = inserter.insert(f);
      EXPECT_FALSE(first.previous_stored.has_value());
      const std::uint64_t exact = test::cpu_twin(gpu, f).count_stored();
      ASSERT_GT(exact, 1000u);
      EXPECT_EQ(first.counters.stored(), exact);
      EXPECT_EQ(gpu.count_stored(), exact);  // counting only: the table stays
      EXPECT_EQ(gpu.count_stored(), exact);
      const auto t0 = std::chrono::steady_clock::now();
      const gl::FrameReport empty = gpu.frame([] {});
      const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      // Pass clocks: positive and within the frame's wall-clock time.
      EXPECT_GT(empty.clear.wall_ms, 0.0);
      EXPECT_LE(empty.clear.wall_ms + empty.gather.wall_ms, wall_ms);
      EXPECT_GE(empty.clear.gpu_ms, 0.0);
      ASSERT_TRUE(empty.previous_stored.has_value());
      EXPECT_EQ(*empty.previous_stored, exact);
      EXPECT_EQ(empty.counters.fragments, 0u);
      const auto table = gpu.read_table();
      EXPECT_EQ(std::count(table.begin(), table.end(), 0u), static_cast<std::ptrdiff_t>(table.size()));
      EXPECT_EQ(gpu.count_stored(), 0u);
    }
  }
}

// A scripted sequence whose content grows then shrinks: each frame's table is
// ResizePolicy::next of the previous table and the previous frame's exact
// count (one frame of latency), never below the screen, with offsets
// regenerated for every size, and each frame's table is the CPU path's.
TEST(GlFrame, AdaptiveSizingFollowsSpec8WithOneFrameOfLatency) {
  gl_context();
  const Extent screen{40, 32};
  const std::vector<std::uint64_t> script{400, 1200, 1500, 1700, 2000, 2000, 1200, 500, 200, 100, 100, 100};
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    gl::GlFrameOptions o;
    o.adaptive = true;
    gl::GlHaBuffer gpu(test::config(screen, {}, test::layout_of(mode), 8), test::random_offsets(6), mode, o);
    gl::ComputeInserter inserter(gpu);
    Extent expected = screen;
    std::optional<std::uint64_t> last_exact;
    bool grew = false, shrank = false;
    for (std::size_t k = 0; k < script.size(); ++k) {
      SCOPED_TRACE("frame " + std::to_string(k));
      const auto f = test::stream(screen, StreamKind::Random, script[k], 100 + k);
      const gl::FrameReport r = inserter.insert(f);
      if (last_exact) {
        const Extent next = o.policy.next(expected, screen, *last_exact);
        grew |= next.area() > expected.area();
        shrank |= next.area() < expected.area();
        EXPECT_EQ(r.resized, next != expected);
        expected = next;
        ASSERT_TRUE(r.previous_stored.has_value());
        EXPECT_EQ(*r.previous_stored, *last_exact);
      }
      ASSERT_EQ(r.table, expected);
      EXPECT_GE(r.table.x, screen.x);
      EXPECT_GE(r.table.y, screen.y);
      EXPECT_EQ(gpu.offsets().table(), r.table);
      const HaBuffer cpu = test::cpu_twin(gpu, f);
      EXPECT_EQ(gpu.read_table(), test::table_words(cpu));
      last_exact = cpu.count_stored();
    }
    EXPECT_TRUE(grew);
    EXPECT_TRUE(shrank);
    EXPECT_EQ(expected, screen);  // shrank back to the geometry rule, not below
  }
}

// Lossless mode: a frame that fails is gathered again into grown tables,
// exactly as the CPU path's lossless build does, and loses nothing.
TEST(GlFrame, LosslessModeRegathersIntoTheCpuPathsTablesAndLosesNothing) {
  gl_context();
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config({32, 32}, {32, 32}, test::layout_of(mode), 4);  // AMAX 15
    StreamOptions so;
    so.kind = StreamKind::Random;
    so.count = 1200;  // more fragments than slots: the screen-sized table must fail
    so.seed = 8;
    const auto f = make_stream(c.screen, so);
    gl::GlFrameOptions o;
    o.max_attempts = 12;
    gl::GlHaBuffer gpu(c, test::random_offsets(2), mode, o);
    const gl::FrameReport r = gl::ComputeInserter(gpu).insert(f);
    const BuildResult cpu = build(c, test::random_offsets(2), f, {}, o.policy, o.max_attempts);
    ASSERT_GT(r.attempts.size(), 1u) << "the stream should fail in the first table";
    EXPECT_GT(r.attempts.front().counters.failures(), 0u);
    EXPECT_TRUE(r.lossless());
    ASSERT_EQ(r.attempts.size(), cpu.attempts.size());
    for (std::size_t i = 0; i < r.attempts.size(); ++i) EXPECT_EQ(r.attempts[i].table, cpu.attempts[i].table);
    EXPECT_EQ(r.table, cpu.buffer.table());
    EXPECT_EQ(gpu.read_table(), test::table_words(cpu.buffer));
    EXPECT_EQ(gpu.read_max_age(), cpu.buffer.max_age().ages());
    EXPECT_EQ(r.counters, cpu.counters);
  }
}

struct HostState {
  GLint program, vertex_array, draw_framebuffer, viewport[4], polygon_mode[2];
  GLboolean blend, depth, cull, scissor;
  GLint storage[7], storage_generic, uniform0, uniform_generic;
  GLint64 start2, size2;
  bool operator==(const HostState& o) const {
    return program == o.program && vertex_array == o.vertex_array && draw_framebuffer == o.draw_framebuffer &&
           std::equal(viewport, viewport + 4, o.viewport) && polygon_mode[0] == o.polygon_mode[0] &&
           blend == o.blend && depth == o.depth && cull == o.cull && scissor == o.scissor &&
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
  for (GLuint i = 0; i < 7; ++i) glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &s.storage[i]);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 2, &s.start2);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 2, &s.size2);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.storage_generic);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &s.uniform0);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.uniform_generic);
  return s;
}

// Host-context use: the host's program, vertex array, framebuffer, viewport,
// capabilities, polygon mode and buffer bindings at our very binding points
// are unchanged by frames (gather and clear pass), counting and resolve.
TEST(GlFrame, EveryPassRestoresTheHostsGlState) {
  gl_context();
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
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, buffers[0], 64, 128);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[1]);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers[1]);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
  glBindBuffer(GL_UNIFORM_BUFFER, buffers[0]);
  const HostState before = host_state();
  {
    const gl::AtomicMode mode = modes().back();
    const BufferConfig c = test::config({24, 24}, {30, 30}, test::layout_of(mode), 6);
    gl::GlFrameOptions o;
    o.adaptive = true;
    o.capture = true;
    gl::GlHaBuffer gpu(c, test::random_offsets(1), mode, o);
    gl::ComputeInserter inserter(gpu);
    const auto f = test::stream(c.screen, StreamKind::Coherent, 500, 1);
    inserter.insert(f);
    EXPECT_TRUE(host_state() == before);
    inserter.insert(f);  // with the clear pass
    EXPECT_TRUE(host_state() == before);
    gpu.count_stored();
    EXPECT_TRUE(host_state() == before);
    gpu.resolve({0.5f, 0.5f, 0.5f});
    EXPECT_TRUE(host_state() == before);
  }
  EXPECT_TRUE(host_state() == before);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  for (GLenum cap : {GL_BLEND, GL_DEPTH_TEST, GL_CULL_FACE, GL_SCISSOR_TEST}) glDisable(cap);
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vertex_array);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(1, &renderbuffer);
  glDeleteBuffers(2, buffers);
}

}  // namespace
}  // namespace habuffer
