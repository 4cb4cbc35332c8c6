// Multisampled records on the GPU path (issue 37): every technique that
// stores lists keeps the CPU's masked records and resolves its image bit for
// bit per pixel; the per-sample resolve into a target of the buffer's
// samples averages to it; a host's multisampled framebuffer gives each
// fragment the rasterizer's coverage (gl_SampleMaskIn); and what the
// library cannot resolve (another sample count, sample shading, a target of
// other samples) is refused in one line, with the host's coverage state
// (alpha-to-coverage, sample mask) neither followed nor changed.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <bit>
#include <map>
#include <set>
#include <functional>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/lossless_build.h"

namespace habuffer {
namespace {

constexpr gl::AtomicMode kMode = gl::AtomicMode::Emulated64;  // L64 colour records on llvmpipe
const Technique kExact[] = {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::PagedLists,
                            Technique::Arrays, Technique::KBuffer};

TechniqueConfig msaa_config(Technique t, Extent screen, std::uint32_t samples, std::size_t fragments) {
  TechniqueConfig c = test::technique_config(t, screen, Layout::L64);
  c.buffer.samples = samples;
  if (uses_pool(t)) c.pool_capacity = 2 * fragments + 64;
  if (uses_layers(t)) c.layers = 32;
  if (t == Technique::Ha) c.buffer.table = Extent{screen.x * 2, screen.y * 2};
  return c;
}

// A colour target of `samples` (1: a plain texture) read back through a
// blit to one sample: the host's MSAA resolve, a box filter of the samples.
class Target {
 public:
  Target(Extent screen, std::uint32_t samples) : screen_(screen) {
    const auto w = static_cast<GLsizei>(screen.x), h = static_cast<GLsizei>(screen.y);
    if (samples > 1) {
      glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &colour_);
      glTextureStorage2DMultisample(colour_, static_cast<GLsizei>(samples), GL_RGBA32F, w, h, GL_TRUE);
    } else {
      glCreateTextures(GL_TEXTURE_2D, 1, &colour_);
      glTextureStorage2D(colour_, 1, GL_RGBA32F, w, h);
    }
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &single_);
    glTextureStorage2D(single_, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &single_framebuffer_);
    glNamedFramebufferTexture(single_framebuffer_, GL_COLOR_ATTACHMENT0, single_, 0);
  }
  ~Target() {
    const GLuint fbs[] = {framebuffer_, single_framebuffer_};
    glDeleteFramebuffers(2, fbs);
    const GLuint textures[] = {colour_, single_};
    glDeleteTextures(2, textures);
  }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  [[nodiscard]] GLuint framebuffer() const { return framebuffer_; }
  void clear(glm::vec4 colour) const { glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, &colour.x); }
  [[nodiscard]] std::vector<glm::vec4> read() const {
    const auto w = static_cast<GLint>(screen_.x), h = static_cast<GLint>(screen_.y);
    glBlitNamedFramebuffer(framebuffer_, single_framebuffer_, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    std::vector<glm::vec4> image(screen_.area());
    glGetTextureImage(single_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.size() * sizeof(glm::vec4)),
                      image.data());
    return image;
  }

 private:
  Extent screen_;
  GLuint colour_ = 0, framebuffer_ = 0, single_ = 0, single_framebuffer_ = 0;
};

class GlMultisampling : public ::testing::Test {
 protected:
  void SetUp() override { test::gl_context(); }
};

TEST_F(GlMultisampling, EveryExactTechniqueStoresTheCpusMaskedListsAndResolvesItsImageBitForBit) {
  const Extent screen{24, 13};
  const glm::vec3 background(0.2f, 0.6f, 0.9f);
  for (std::uint32_t samples : {2u, 4u, 8u}) {
    const std::vector<Fragment> frags = test::covered_stream(screen, 1200, samples, samples, StreamKind::Random);
    for (Technique t : kExact) {
      SCOPED_TRACE(to_string(t) + " at " + std::to_string(samples) + " samples");
      const TechniqueConfig c = msaa_config(t, screen, samples, frags.size());
      gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, kMode));
      const gl::FrameReport report = gl::ComputeInserter(gpu).insert(frags);
      const TechniqueBuild cpu = build_technique(c, OffsetSource{}, frags, InsertOptions{});
      EXPECT_EQ(report.counters, cpu.counters);
      EXPECT_EQ(report.counters.failures(), 0u);
      EXPECT_GT(report.counters.invalid, 0u) << "masks of no sample are counted invalid";
      EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), test::traversed_lists(*cpu.buffer));
      EXPECT_EQ(test::resolve_to_image(gpu, background),
                cpu.buffer->composite_image(std::vector<glm::vec3>(screen.area(), background)));
    }
  }
}

TEST_F(GlMultisampling, ThePerSampleResolveIntoATargetOfTheBuffersSamplesBlitsToThePerPixelResolve) {
  const Extent screen{20, 16};
  const std::uint32_t samples = 4;
  const std::vector<Fragment> frags = test::covered_stream(screen, 1500, 3, samples, StreamKind::Random);
  for (Technique t : {Technique::Ha, Technique::Lists, Technique::KBuffer}) {
    SCOPED_TRACE(to_string(t));
    gl::GlFrameDriver gpu(gl::make_gl_technique(msaa_config(t, screen, samples, frags.size()), OffsetSource{}, kMode));
    gl::ComputeInserter(gpu).insert(frags);
    const std::vector<glm::vec4> per_pixel = test::resolve_to_image(gpu, glm::vec3(1.0f, 0.5f, 0.0f));
    const Target target(screen, samples);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer());
    gpu.resolve(glm::vec3(1.0f, 0.5f, 0.0f));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    EXPECT_LT(test::largest_difference(target.read(), per_pixel), 1e-6f);
  }
}

// A rectangle of two triangles from the screen's left side to the vertical
// line x = kEdge through the middle of pixel column kEdge - 0.5, drawn into
// a host's framebuffer with a colour attachment of four samples: the
// expected mask of an edge pixel comes from the framebuffer's own sample
// positions, and the pixels the shared diagonal crosses get two fragments
// of one depth and colour whose masks split the pixel.
constexpr float kEdge = 8.5f;
constexpr const char* kEdgeVertex = R"(#version 450 core
uniform float edge_x;
void main() {
  const vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                  vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
  vec2 c = corners[gl_VertexID];
  gl_Position = vec4(c.x > 0.0 ? edge_x : -1.0, c.y, 0.25, 1.0);
}
)";
constexpr const char* kEdgeMain = R"(
void main() {
  habuffer_insert(uvec2(gl_FragCoord.xy), gl_FragCoord.z, ha_pack_rgba(vec4(1.0, 0.0, 0.0, 0.5)));
  discard;
}
)";

class EdgeHost {
 public:
  EdgeHost(Extent screen, std::uint32_t samples) : screen_(screen) {
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &colour_);
    glTextureStorage2DMultisample(colour_, static_cast<GLsizei>(samples), GL_RGBA8, static_cast<GLsizei>(screen.x),
                                  static_cast<GLsizei>(screen.y), GL_TRUE);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
    glCreateVertexArrays(1, &vertex_array_);
  }
  ~EdgeHost() {
    glDeleteTextures(1, &colour_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteVertexArrays(1, &vertex_array_);
  }
  EdgeHost(const EdgeHost&) = delete;
  EdgeHost& operator=(const EdgeHost&) = delete;

  // The draw framebuffer's sample positions (in the pixel, [0, 1)^2).
  [[nodiscard]] std::vector<glm::vec2> sample_positions() const {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    std::vector<glm::vec2> out(static_cast<std::size_t>(samples));
    for (GLint s = 0; s < samples; ++s) glGetMultisamplefv(GL_SAMPLE_POSITION, static_cast<GLuint>(s), &out[s].x);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    return out;
  }

  gl::FrameReport draw(gl::GlFrameDriver& gpu, const std::function<void()>& inside = {}) const {
    const auto program = gl::ShaderProgram::graphics(
        kEdgeVertex, gpu.module_source(gl::ShaderStage::Fragment) + kEdgeMain, "edge host gather");
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
    if (inside) inside();
    const gl::FrameReport report = gpu.frame([&] {
      glUseProgram(program.id());
      program.set("edge_x", 2.0f * kEdge / static_cast<float>(screen_.x) - 1.0f);
      glBindVertexArray(vertex_array_);
      glDrawArrays(GL_TRIANGLES, 0, 6);
      glBindVertexArray(0);
      glUseProgram(0);
    });
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    return report;
  }

 private:
  Extent screen_;
  GLuint colour_ = 0, framebuffer_ = 0, vertex_array_ = 0;
};

TEST_F(GlMultisampling, AHostsFourSampleFramebufferGivesEachFragmentTheRasterizersCoverage) {
  const Extent screen{16, 8};
  const EdgeHost host(screen, 4);
  const std::vector<glm::vec2> positions = host.sample_positions();
  ASSERT_EQ(positions.size(), 4u);
  std::uint32_t edge_mask = 0;  // the samples of column 8 left of x = 8.5
  for (std::size_t s = 0; s < positions.size(); ++s)
    if (8.0f + positions[s].x < kEdge) edge_mask |= 1u << s;
  ASSERT_NE(edge_mask, 0u);
  ASSERT_NE(edge_mask, 0xFu) << "the edge must split the pixel's samples";
  for (Technique t : {Technique::Ha, Technique::Lists}) {
    SCOPED_TRACE(to_string(t));
    const TechniqueConfig c = msaa_config(t, screen, 4, 4 * screen.area());
    gl::GlFrameOptions options;
    options.capture = true;
    gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, kMode), options);
    const gl::FrameReport report = host.draw(gpu);
    const std::vector<Fragment> captured = gpu.read_capture();
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> union_of, bits;
    for (const Fragment& f : captured) {
      union_of[{f.x, f.y}] |= f.coverage;
      bits[{f.x, f.y}] += static_cast<std::uint32_t>(std::popcount(f.coverage));
    }
    ASSERT_EQ(union_of.size(), 9u * screen.y) << "columns 0 to 8 of every row";
    for (const auto& [p, mask] : union_of) {
      EXPECT_EQ(mask, p.first == 8 ? edge_mask : 0xFu) << p.first << "," << p.second;
      EXPECT_EQ(bits[p], static_cast<std::uint32_t>(std::popcount(mask))) << "the two triangles' masks are disjoint";
    }
    EXPECT_GT(captured.size(), union_of.size()) << "the diagonal splits some pixels between the triangles";
    const TechniqueBuild cpu = build_technique(c, OffsetSource{}, captured, InsertOptions{});
    EXPECT_EQ(report.counters, cpu.counters);
    EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), test::traversed_lists(*cpu.buffer));
    const glm::vec3 white(1.0f);
    const std::vector<glm::vec4> image = test::resolve_to_image(gpu, white);
    EXPECT_EQ(image, cpu.buffer->composite_image(std::vector<glm::vec3>(screen.area(), white)));
    const float covered = static_cast<float>(std::popcount(edge_mask)) / 4.0f;
    for (std::uint32_t y = 0; y < screen.y; ++y) {
      const std::size_t row = std::size_t{y} * screen.x;
      const float alpha = 128.0f / 255.0f;  // 0.5 as packUnorm4x8 stores it
      for (std::uint32_t x = 0; x < 8; ++x)
        EXPECT_NEAR(image[row + x].g, 1.0f - alpha, 1e-6f) << "every sample sees one record";
      EXPECT_NEAR(image[row + 8].g, 1.0f - alpha * covered, 1e-6f) << "the edge pixel: its samples' share of red";
      EXPECT_EQ(image[row + 9].g, 1.0f);
    }
  }
}

TEST_F(GlMultisampling, AnotherSampleCountSampleShadingOrTargetIsRefusedInOneLine) {
  const Extent screen{16, 8};
  const EdgeHost host(screen, 4);
  const auto refused = [](const std::function<void()>& call, const std::string& words) {
    try {
      call();
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const gl::GlError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  gl::GlFrameDriver single(gl::make_gl_technique(msaa_config(Technique::Lists, screen, 1, 512), OffsetSource{}, kMode));
  refused([&] { (void)host.draw(single); }, "framebuffer of 4 samples per pixel into a buffer of 1");
  gl::GlFrameDriver two(gl::make_gl_technique(msaa_config(Technique::Lists, screen, 2, 512), OffsetSource{}, kMode));
  refused([&] { (void)host.draw(two); }, "framebuffer of 4 samples per pixel into a buffer of 2");
  gl::GlFrameDriver four(gl::make_gl_technique(msaa_config(Technique::Ha, screen, 4, 512), OffsetSource{}, kMode));
  refused([&] { (void)host.draw(four, [] { glEnable(GL_SAMPLE_SHADING); }); }, "sample shading is on");
  glDisable(GL_SAMPLE_SHADING);
  EXPECT_EQ(host.draw(four).counters.failures(), 0u) << "the same host at the buffer's samples";
  const Target four_samples(screen, 4);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, four_samples.framebuffer());
  refused([&] { (void)two.resolve(glm::vec3(1.0f)); }, "has 4 samples per pixel and the buffer 2");
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

TEST_F(GlMultisampling, ResolveOverIgnoresAndKeepsTheHostsAlphaToCoverageAndSampleMask) {
  const Extent screen{20, 12};
  const std::vector<Fragment> frags = test::covered_stream(screen, 900, 5, 4, StreamKind::Random);
  gl::GlFrameDriver gpu(gl::make_gl_technique(msaa_config(Technique::Lists, screen, 4, frags.size()), OffsetSource{}, kMode));
  gl::ComputeInserter(gpu).insert(frags);
  const auto over = [&](bool host_coverage_state) {
    const Target target(screen, 4);
    target.clear(glm::vec4(0.1f, 0.7f, 0.3f, 1.0f));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer());
    if (host_coverage_state) {
      glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      glEnable(GL_SAMPLE_MASK);
      glSampleMaski(0, 0x1u);
    }
    gpu.resolve_over();
    if (host_coverage_state) {
      EXPECT_TRUE(glIsEnabled(GL_SAMPLE_ALPHA_TO_COVERAGE));
      EXPECT_TRUE(glIsEnabled(GL_SAMPLE_MASK));
      GLint mask = 0;
      glGetIntegeri_v(GL_SAMPLE_MASK_VALUE, 0, &mask);
      EXPECT_EQ(mask, 0x1);
      glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      glDisable(GL_SAMPLE_MASK);
      glSampleMaski(0, ~0u);
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    return target.read();
  };
  const std::vector<glm::vec4> plain = over(false);
  EXPECT_EQ(over(true), plain);
  std::size_t blended = 0;
  for (const glm::vec4& p : plain) blended += p != glm::vec4(0.1f, 0.7f, 0.3f, 1.0f) ? 1 : 0;
  EXPECT_GT(blended, 0u);
}

}  // namespace
}  // namespace habuffer
