// The GPU path on the machine's OpenGL (Mesa llvmpipe here): headless
// context, shader error reporting, state restoration, and the shared GLSL
// insert building the CPU path's table bit for bit.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "test_support.h"

namespace habuffer {
namespace {

gl::EglContext& context() {
  static gl::EglContext ctx;  // one per process: llvmpipe contexts are costly
  ctx.make_current();
  return ctx;
}

TEST(Gl, HeadlessContextIsOpenGl45CoreWithNative32) {
  context();
  const gl::GlInfo info = gl::query_gl_info();
  EXPECT_NE(info.version.find("4.5"), std::string::npos) << info.version;
  const auto modes = gl::runnable_atomic_modes(info);
  ASSERT_FALSE(modes.empty());
  EXPECT_EQ(modes.front(), gl::AtomicMode::Native32);
}

TEST(Gl, ShaderErrorsCarryTheCompileLog) {
  context();
  try {
    gl::ShaderProgram::compute("#version 450\nlayout(local_size_x = 1) in;\nvoid main() { no_such_function(); }\n",
                               "broken shader");
    FAIL() << "compiled a broken shader";
  } catch (const gl::GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("broken shader does not compile"), std::string::npos) << what;
    EXPECT_NE(what.find("no_such_function"), std::string::npos) << what;
  }
}

TEST(Gl, KhrDebugErrorsOfOurContextBecomeExceptions) {
  context();
  std::vector<std::string> logged;
  gl::set_log_sink([&](const std::string& m) { logged.push_back(m); });
  gl::set_throw_on_gl_error(true);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 100000, 0);  // binding index far beyond the limit: GL_INVALID_VALUE
  EXPECT_THROW(gl::check_gl_errors("binding test"), gl::GlError);
  EXPECT_FALSE(logged.empty());
  EXPECT_NO_THROW(gl::check_gl_errors("nothing pending"));
  gl::set_throw_on_gl_error(false);
  gl::set_log_sink(nullptr);
}

TEST(Gl, SharedGlslCompilesForTheRunnableModes) {
  context();
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info()))
    EXPECT_NO_THROW(gl::ShaderProgram::compute(gl::insert_stream_compute(mode), "insert " + gl::to_string(mode)));
}

TEST(Gl, ComputeInsertRestoresTheHostsProgramAndBufferBindings) {
  context();
  GLuint host_buffer = 0;
  glCreateBuffers(1, &host_buffer);
  glNamedBufferData(host_buffer, 256, nullptr, GL_STATIC_DRAW);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, host_buffer, 64, 128);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, host_buffer);
  auto host_program = gl::ShaderProgram::compute("#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n", "host");
  glUseProgram(host_program.id());
  {
    const BufferConfig c = test::config({8, 8}, {8, 8}, Layout::L32, 6);
    gl::ComputeInserter gpu(c, OffsetSequence::random(c.table, 63, 1), gl::AtomicMode::Native32);
    gpu.insert(test::stream({8, 8}, StreamKind::Random, 40, 1));
  }
  GLint program = 0, bound = 0, generic = 0;
  GLint64 start = 0, size = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &program);
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 2, &bound);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 2, &start);
  glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 2, &size);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic);
  EXPECT_EQ(static_cast<GLuint>(program), host_program.id());
  EXPECT_EQ(static_cast<GLuint>(bound), host_buffer);
  EXPECT_EQ(start, 64);
  EXPECT_EQ(size, 128);
  EXPECT_EQ(static_cast<GLuint>(generic), host_buffer);
  glUseProgram(0);
  glDeleteBuffers(1, &host_buffer);
}

// SPEC 9 across paths: the GPU's compute insertion and the CPU path build
// the same table, bit for bit, and the same max-age table when nothing
// fails, in every atomic mode this machine runs (native32 with L32,
// emulated64 with L64); several sizes including a table exactly the screen,
// age bits 4 and 8.
TEST(Gl, EveryAtomicModeBuildsTheCpuTableBitForBit) {
  context();
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info())) {
    const Layout layout = mode == gl::AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    SCOPED_TRACE(gl::to_string(mode));
    struct Case {
      Extent screen, table;
      std::uint32_t age_bits;
      StreamKind kind;
      double load;
    };
    for (const Case& k : {Case{{32, 24}, {32, 24}, 8, StreamKind::Coherent, 0.8},
                          Case{{40, 30}, {57, 41}, 4, StreamKind::Random, 0.6},
                          Case{{64, 64}, {80, 64}, 8, StreamKind::Random, 0.9},
                          Case{{16, 48}, {16, 48}, 4, StreamKind::Coherent, 1.1}}) {
      SCOPED_TRACE(k.screen.str() + " in " + k.table.str());
      const BufferConfig c = test::config(k.screen, k.table, layout, k.age_bits, 8);
      const auto offsets = OffsetSequence::random(k.table, c.record_layout().max_age(), 9);
      auto f = test::stream(k.screen, k.kind, static_cast<std::uint64_t>(k.load * static_cast<double>(k.table.area())), 4);
      f[f.size() / 3].depth = std::numeric_limits<float>::quiet_NaN();
      HaBuffer cpu(c, offsets);
      const Counters nc = cpu.insert(f);
      gl::ComputeInserter gpu(c, offsets, mode);
      const Counters ng = gpu.insert(f);
      ASSERT_EQ(nc.failed_iter + ng.failed_iter, 0u);
      const auto table = gpu.read_table();
      for (std::uint64_t s = 0; s < cpu.slot_count(); ++s) ASSERT_EQ(table[s], cpu.slot(s)) << "slot " << s;
      EXPECT_EQ(ng.stored(), nc.stored());
      EXPECT_EQ(ng.invalid, nc.invalid);
      EXPECT_EQ(ng.duplicates + ng.failed_age, nc.duplicates + nc.failed_age);
      EXPECT_GT(nc.stored(), f.size() / 2);
      if (nc.failures() + ng.failures() == 0) {
        EXPECT_EQ(gpu.read_max_age(), cpu.max_age().ages());
        EXPECT_EQ(ng, nc);
      }
      // The comparison bites: other offsets give another table.
      gl::ComputeInserter other(c, OffsetSequence::random(k.table, c.record_layout().max_age(), 10), mode);
      other.insert(f);
      EXPECT_NE(other.read_table(), table);
    }
  }
}

}  // namespace
}  // namespace habuffer
