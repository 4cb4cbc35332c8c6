// The translucent shadow map's lookup on the GPU: ha_transmittance of the
// HA-buffer's GLSL module (the shared walk of shared/ha_traverse.glsl), run
// in a host compute shader over a light buffer the GPU gathered, gives the
// CPU's transmittance bit for bit at every pixel, receiver depth and bias.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cstring>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_support.h"
#include "habuffer/gl/host_glsl_files.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/transmittance.h"

namespace habuffer {
namespace {

constexpr const char* kLookupMain = R"(
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) writeonly buffer LookupOut { float lookup_out[]; };
uniform uint lookup_code;
uniform uint lookup_bias;
void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, habuffer_screen_size))) return;
  lookup_out[p.x + p.y * habuffer_screen_size.x] = ha_transmittance(p, lookup_code, lookup_bias);
}
)";

TEST(GlTransmittance, TheGpusLookupGivesTheCpusTransmittanceBitForBit) {
  test::gl_context();
  for (gl::AtomicMode mode : gl::runnable_atomic_modes(gl::query_gl_info())) {
    if (mode == gl::AtomicMode::Native32) continue;  // L32 records carry no opacity
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config({23, 17}, {48, 40}, Layout::L64, 8);
    gl::GlHaBuffer gpu(c, test::random_offsets(7), mode);
    gl::ComputeInserter inserter(gpu);
    const std::vector<Fragment> frags = test::grid_stream(c.screen, 1200, 5, 1);
    ASSERT_EQ(inserter.insert(frags).counters.failures(), 0u);
    const HaBuffer cpu = test::cpu_twin(gpu, frags);
    const gl::ShaderProgram program =
        gl::ShaderProgram::compute(gpu.module_source(gl::ShaderStage::Compute) + kLookupMain, "transmittance lookup");
    const std::uint64_t pixels = c.screen.area();
    GLuint out = 0;
    glCreateBuffers(1, &out);
    glNamedBufferStorage(out, static_cast<GLsizeiptr>(pixels * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    const RecordLayout layout = c.record_layout();
    for (const float receiver : {0.0f, 0.3f, 0.7f, 1.0f})
      for (const std::uint32_t bias : {0u, 5u, 1u << 16}) {
        const std::uint32_t code = layout.depth_code(receiver);
        gpu.bind();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, out);
        glUseProgram(program.id());
        program.set("lookup_code", code);
        program.set("lookup_bias", bias);
        glDispatchCompute((c.screen.x + 7) / 8, (c.screen.y + 7) / 8, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<float> got(pixels);
        glGetNamedBufferSubData(out, 0, static_cast<GLsizeiptr>(pixels * 4), got.data());
        int shadowed = 0;
        for (std::uint32_t y = 0; y < c.screen.y; ++y) {
          for (std::uint32_t x = 0; x < c.screen.x; ++x) {
            const float want = cpu.transmittance(x, y, code, bias), have = got[x + y * c.screen.x];
            std::uint32_t a = 0, b = 0;
            std::memcpy(&a, &want, 4);
            std::memcpy(&b, &have, 4);
            ASSERT_EQ(a, b) << "pixel " << x << "," << y << " receiver " << receiver << " bias " << bias;
            shadowed += want < 1.0f ? 1 : 0;
          }
        }
        if (receiver == 1.0f && bias == 0u) {
          EXPECT_GT(shadowed, 0);
        }
      }
    glDeleteBuffers(1, &out);
    glUseProgram(0);
  }
}

// A view frame of another technique (lists) reads the light buffer beside
// its own module: light_lookup_part instantiates the shared walk under hs_,
// and habuffer_shadow_transmittance gives the CPU's transmittance bit for
// bit, by light pixel and depth and by world point (an orthographic light
// whose matrices map a point to its pixel and depth exactly).
TEST(GlTransmittance, AViewOfAnotherTechniqueLooksTheLightBufferUpAsTheCpuDoes) {
  test::gl_context();
  const gl::GlInfo info = gl::query_gl_info();
  if (!info.int64_types) GTEST_SKIP() << "no 64-bit shader integers: no L64 light buffer";
  const gl::AtomicMode mode = info.atomic_int64 ? gl::AtomicMode::Native64 : gl::AtomicMode::Emulated64;
  const BufferConfig lc = test::config({16, 16}, {40, 32}, Layout::L64, 8);
  gl::GlHaBuffer light(lc, test::random_offsets(3), mode);
  gl::ComputeInserter inserter(light);
  const std::vector<Fragment> frags = test::grid_stream(lc.screen, 900, 8, 1);
  ASSERT_EQ(inserter.insert(frags).counters.failures(), 0u);
  const HaBuffer cpu = test::cpu_twin(light, frags);
  // The view: lists on another screen, its own module and buffers at the default points.
  TechniqueConfig view_config = test::technique_config(Technique::Lists, {8, 8}, Layout::L64);
  view_config.pool_capacity = 64;
  gl::GlFrameDriver view(gl::make_gl_technique(view_config, {}, mode));
  gl::GlLightMapping mapping;
  mapping.projection = glm::ortho(0.0f, 16.0f, 0.0f, 16.0f, 0.0f, 1.0f);  // eye (x, y, -t) to pixel (x, y), depth t
  const std::uint32_t bias = 2;
  gl::GlShadowLookup lookup(light.container(), mapping, bias, view.bindings());
  const std::string main = R"(
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) writeonly buffer LookupOut { float lookup_out[]; };
uniform float lookup_depth;
void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, uvec2(16u)))) return;
  uint i = p.x + p.y * 16u;
  lookup_out[2u * i] = habuffer_shadow_transmittance(p, lookup_depth);
  lookup_out[2u * i + 1u] = habuffer_shadow_transmittance(vec3(vec2(p) + 0.5, -lookup_depth));
}
)";
  const gl::ShaderProgram program = gl::ShaderProgram::compute(
      view.module_source(gl::ShaderStage::Compute) + gl::light_lookup_part(lookup.bindings(), mode) + main, "view lookup");
  GLuint out = 0;
  glCreateBuffers(1, &out);
  glNamedBufferStorage(out, 2 * 256 * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
  const RecordLayout layout = lc.record_layout();
  // Each pixel's two lookups (by pixel and depth, by world point) at `depth`, through `p`.
  const auto run = [&](const gl::ShaderProgram& p, float depth) {
    view.bind();
    lookup.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, out);
    glUseProgram(p.id());
    p.set("lookup_depth", depth);
    glDispatchCompute(2, 2, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> values(512);
    glGetNamedBufferSubData(out, 0, 512 * 4, values.data());
    return values;
  };
  int shadowed = 0;
  for (const float depth : {0.25f, 0.5f, 0.9375f}) {
    const std::vector<float> got = run(program, depth);
    for (std::uint32_t y = 0; y < 16; ++y) {
      for (std::uint32_t x = 0; x < 16; ++x) {
        const float want = cpu.transmittance(x, y, layout.depth_code(depth), bias);
        const std::uint32_t i = x + y * 16;
        EXPECT_EQ(got[2 * i], want) << "pixel " << x << "," << y << " depth " << depth;
        EXPECT_EQ(got[2 * i + 1], want) << "world point over pixel " << x << "," << y << " depth " << depth;
        shadowed += want < 1.0f ? 1 : 0;
      }
    }
  }
  EXPECT_GT(shadowed, 0);
  // The light buffer's table changes (as adaptive sizing or lossless growth
  // change it): bind() writes the block again, and the lookup follows.
  light.resize({56, 48});
  ASSERT_EQ(inserter.insert(frags).counters.failures(), 0u);
  const HaBuffer grown = test::cpu_twin(light, frags);
  const std::vector<float> got = run(program, 0.9375f);
  for (std::uint32_t i = 0; i < 256; ++i)
    EXPECT_EQ(got[2 * i], grown.transmittance(i % 16, i / 16, layout.depth_code(0.9375f), bias)) << "pixel " << i;
  EXPECT_THROW((void)gl::light_lookup_part(lookup.bindings(), gl::AtomicMode::Native32), gl::GlError);
  // The installed files (file-based pipelines): the lists' compute file, then
  // the light lookup's, at their default points, give the same lookups.
  std::map<std::string, std::string> files;
  for (const gl::GlslFile& f : gl::host_glsl_files()) files[f.path] = f.text;
  const std::string dir = gl::to_string(mode) + "/";
  ASSERT_EQ(files.count(dir + "light_lookup.glsl"), 1u);
  const gl::ShaderProgram installed = gl::ShaderProgram::compute(
      "#version 450 core\n" + files[dir + "extensions.glsl"] + files[dir + "lists.comp.glsl"] +
          files[dir + "light_lookup.glsl"] + main,
      "view lookup from the installed files");
  const std::vector<float> from_files = run(installed, 0.9375f);
  EXPECT_TRUE(from_files == got);
  glDeleteBuffers(1, &out);
  glUseProgram(0);
}

}  // namespace
}  // namespace habuffer
