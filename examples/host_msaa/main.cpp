// A host OpenGL app that renders into its own 4x multisampled framebuffer
// (RGBA8 colour and 24-bit depth, four samples each): an opaque floor and an
// opaque slanted wedge, then three translucent triangles with slanted edges,
// submitted in no particular order, and the host's MSAA resolve (a blit).
//
// Order-independent transparency that stays antialiased comes from habuffer
// through the lines that end in the habuffer tag: a GPU HA-buffer of four
// samples per pixel (BufferConfig::samples), the module in the triangles'
// fragment shader, which declares post_depth_coverage so each fragment's
// coverage mask (gl_SampleMaskIn) holds only the samples in front of the
// host's multisampled depth, the draw wrapped in one frame, and
// resolve_over, which into a target of the buffer's samples composites
// each sample's own records over that sample's opaque colour.
//
// Exits 0 when the resolved pixels match an exact per-sample reference
// computed by hand here (each sample at the framebuffer's own sample
// position: its opaque surface, the triangles covering it in front, sorted
// and blended, the samples averaged) within 1.5/255, and the image has
// edge pixels the triangles only partly cover; 1 otherwise.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "../host_gl.h"

#include <habuffer/gl.h>  // [habuffer]

namespace {

using host_gl::check;
using host_gl::link_program;

constexpr int kWidth = 96, kHeight = 72, kSamples = 4;

// A triangle in normalized device coordinates at one depth (NDC z), with a
// straight-alpha colour.
struct Triangle {
  std::array<float, 6> xy;
  float depth, r, g, b, a;
};
const Triangle kFloor[2] = {{{-1, -1, 1, -1, 1, 1}, 0.9f, 0.2f, 0.2f, 0.2f, 1.0f},
                            {{-1, -1, 1, 1, -1, 1}, 0.9f, 0.2f, 0.2f, 0.2f, 1.0f}};
const Triangle kWedge{{0.15f, -0.85f, 0.95f, -0.3f, 0.4f, 0.9f}, -0.2f, 0.9f, 0.9f, 0.1f, 1.0f};  // in front of every pane
const Triangle kPanes[3] = {{{-0.9f, -0.7f, 0.8f, -0.4f, -0.3f, 0.85f}, -0.5f, 1.0f, 0.0f, 0.0f, 0.6f},  // nearest
                            {{-0.8f, 0.6f, 0.7f, 0.8f, 0.1f, -0.9f}, 0.6f, 0.0f, 0.0f, 1.0f, 0.6f},     // farthest
                            {{-0.95f, 0.1f, 0.9f, -0.2f, 0.3f, 0.95f}, 0.1f, 0.0f, 1.0f, 0.0f, 0.5f}};  // middle

const char* const kVertex = R"(#version 450 core
uniform vec2 corners[3];
uniform float depth;
void main() { gl_Position = vec4(corners[gl_VertexID], depth, 1.0); }
)";
const char* const kOpaqueFragment = R"(#version 450 core
uniform vec4 colour;
layout(location = 0) out vec4 out_colour;
void main() { out_colour = colour; }
)";
// The triangles' gather shader: the module, then ours. post_depth_coverage:       // [habuffer]
// gl_SampleMaskIn holds the samples that passed the host's depth test.            // [habuffer]
const char* const kPaneHeader = "#extension GL_ARB_post_depth_coverage : require\n";  // [habuffer]
const char* const kPaneMain = R"(                                              // [habuffer]
layout(early_fragment_tests, post_depth_coverage) in;                          // [habuffer]
uniform vec4 colour;                                                           // [habuffer]
void main() { habuffer_insert_here(colour); }                                  // [habuffer]
)";                                                                            // [habuffer]

void draw(GLuint program, const Triangle& t) {
  glUseProgram(program);
  glUniform2fv(glGetUniformLocation(program, "corners"), 3, t.xy.data());
  glUniform1f(glGetUniformLocation(program, "depth"), t.depth);
  glUniform4f(glGetUniformLocation(program, "colour"), t.r, t.g, t.b, t.a);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Whether NDC point (x, y) lies inside triangle t (either winding).
bool covers(const Triangle& t, float x, float y) {
  const auto edge = [&](int i, int j) {
    return (t.xy[2 * j] - t.xy[2 * i]) * (y - t.xy[2 * i + 1]) - (t.xy[2 * j + 1] - t.xy[2 * i + 1]) * (x - t.xy[2 * i]);
  };
  const float e0 = edge(0, 1), e1 = edge(1, 2), e2 = edge(2, 0);
  return (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
}

// Whether NDC point (x, y) lies within 1/128 pixel of an edge of any
// triangle: the rasterizer snaps vertices to its subpixel grid (1/256
// pixel), so such a sample may fall on either side, and the reference
// leaves its pixel unchecked.
bool near_an_edge(float x, float y) {
  const auto near = [&](const Triangle& t) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const double ex = (t.xy[2 * j] - t.xy[2 * i]) * kWidth / 2.0, ey = (t.xy[2 * j + 1] - t.xy[2 * i + 1]) * kHeight / 2.0;
      const double px = (x - t.xy[2 * i]) * kWidth / 2.0, py = (y - t.xy[2 * i + 1]) * kHeight / 2.0;
      const double along = (ex * px + ey * py) / (ex * ex + ey * ey);  // 0..1 on the edge itself
      if (along >= 0.0 && along <= 1.0 && std::fabs(ex * py - ey * px) / std::hypot(ex, ey) < 1.0 / 128.0)
        return true;  // within 1/128 pixel of the edge
    }
    return false;
  };
  if (near(kWedge)) return true;
  for (const Triangle& t : kPanes)
    if (near(t)) return true;
  return false;
}

// One sample at NDC (x, y): the nearest opaque surface, the panes in front
// of it covering the sample, nearest first, blended front to back over it.
std::array<double, 3> expected_sample(float x, float y) {
  const Triangle& opaque = covers(kWedge, x, y) ? kWedge : kFloor[0];
  std::vector<const Triangle*> panes;
  for (const Triangle& t : kPanes)
    if (covers(t, x, y)) panes.push_back(&t);
  return host_gl::blend_in_front(panes, opaque);
}

}  // namespace

int main() {
  try {
    host_gl::make_context();
    const GLuint multisampled = host_gl::make_framebuffer(kWidth, kHeight, kSamples);
    const GLuint resolved = host_gl::make_framebuffer(kWidth, kHeight);
    GLuint vertex_array = 0;
    glCreateVertexArrays(1, &vertex_array);
    const GLuint opaque = link_program(kVertex, kOpaqueFragment);
    // The framebuffer's own sample positions, for the reference.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, multisampled);
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    check(samples == kSamples, "the framebuffer has " + std::to_string(samples) + " samples, not 4");
    std::array<std::array<float, 2>, kSamples> position{};
    for (int s = 0; s < kSamples; ++s) glGetMultisamplefv(GL_SAMPLE_POSITION, static_cast<GLuint>(s), position[s].data());

    namespace hb = habuffer;                                                                  // [habuffer]
    const auto mode = hb::gl::chosen_atomic_mode(hb::gl::query_gl_info(), hb::Layout::L64);  // [habuffer]
    check(mode.has_value(), "this OpenGL has no 64-bit shader integers");                    // [habuffer]
    hb::BufferConfig config;                                                                  // [habuffer]
    config.screen = {kWidth, kHeight};                                                        // [habuffer]
    config.samples = kSamples;  // a coverage mask per record, resolved per sample           // [habuffer]
    hb::gl::GlHaBuffer oit(config, hb::OffsetSource{}, *mode);                               // [habuffer]
    const std::string module = oit.module_source(hb::gl::ShaderStage::Fragment, kPaneHeader);  // [habuffer]
    const GLuint panes = link_program(kVertex, module + kPaneMain);                           // [habuffer]

    glBindVertexArray(vertex_array);
    glViewport(0, 0, kWidth, kHeight);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    for (const Triangle& t : kFloor) draw(opaque, t);
    draw(opaque, kWedge);
    // The translucent triangles: depth tested against the opaque surfaces
    // per sample, no depth writes.
    glDepthMask(GL_FALSE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the gather inserts, writes nothing  // [habuffer]
    const hb::gl::FrameReport report = oit.frame([&] {                                        // [habuffer]
      for (const Triangle& t : kPanes) draw(panes, t);                                        // [habuffer]
    });                                                                                       // [habuffer]
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);                                          // [habuffer]
    glDepthMask(GL_TRUE);
    oit.resolve_over();  // per sample: each sample's records over its opaque colour          // [habuffer]
    const hb::Counters& c = report.counters;                                                  // [habuffer]
    std::printf("habuffer: %llu fragments, %llu lost\n", (unsigned long long)c.fragments, (unsigned long long)c.failures());  // [habuffer]
    // The host's MSAA resolve.
    glBlitNamedFramebuffer(multisampled, resolved, 0, 0, kWidth, kHeight, 0, 0, kWidth, kHeight, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);

    int partial = 0, ambiguous = 0;  // pixels whose samples see different surfaces; pixels left unchecked
    const auto expected_pixel = [&](int px, int py) {
      std::array<double, 3> sum{0, 0, 0};
      std::array<double, 3> first{};
      bool uniform = true;
      for (int s = 0; s < kSamples; ++s) {
        const float x = (static_cast<float>(px) + position[s][0]) / kWidth * 2.0f - 1.0f;
        const float y = (static_cast<float>(py) + position[s][1]) / kHeight * 2.0f - 1.0f;
        if (near_an_edge(x, y)) {
          ++ambiguous;
          return std::vector<float>{-1.0f, -1.0f, -1.0f};
        }
        const std::array<double, 3> v = expected_sample(x, y);
        if (s == 0) first = v;
        uniform = uniform && v == first;
        for (int k = 0; k < 3; ++k) sum[k] += v[k];
      }
      partial += uniform ? 0 : 1;
      return std::vector<float>{static_cast<float>(sum[0] / kSamples), static_cast<float>(sum[1] / kSamples),
                                static_cast<float>(sum[2] / kSamples)};
    };
    const int wrong = host_gl::count_wrong_channels(resolved, kWidth, kHeight, expected_pixel, "host_msaa");
    std::printf("host_msaa: %d pixels whose samples differ (edges), %d with a sample on an edge unchecked\n", partial,
                ambiguous);
    return wrong == 0 && partial > 100 && ambiguous < partial / 4 && c.failures() == 0 ? 0 : 1;  // [habuffer]
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_msaa: %s\n", e.what());
    return 1;
  }
}
