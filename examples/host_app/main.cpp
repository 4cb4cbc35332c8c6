// A host OpenGL app: its own headless EGL context, its own shaders, its own
// framebuffer (RGBA8 colour, 24-bit depth). It draws an opaque floor and an
// opaque box, then three translucent panes, submitted in no particular order.
//
// Order-independent transparency comes from habuffer through the lines that
// end in the habuffer tag (grep -c '// \[habuffer\]$' main.cpp counts them):
// a GPU HA-buffer, the GLSL module in the panes' fragment shader, the panes'
// draw wrapped in one frame, and a resolve that blends the sorted panes over
// the opaque image. Without those lines (the panes drawn with the opaque
// program, `return wrong == 0 ? 0 : 1;`) this is the app before habuffer:
// plain blending in submission order, off by up to 0.5 where panes overlap
// out of order.
//
// Exits 0 when the pixels read back match the front-to-back blend computed
// by hand here (within 1.5/255), 1 otherwise.
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

constexpr int kWidth = 160, kHeight = 120;

// One axis-aligned rectangle in normalized device coordinates at a depth,
// with a straight-alpha colour.
struct Quad {
  float x0, y0, x1, y1, depth;
  float r, g, b, a;
};
const Quad kFloor{-1.0f, -1.0f, 1.0f, 1.0f, 0.9f, 0.2f, 0.2f, 0.2f, 1.0f};
const Quad kBox{0.5f, -0.5f, 0.9f, 0.5f, 0.1f, 0.9f, 0.9f, 0.1f, 1.0f};  // in front of every pane
const Quad kPanes[3] = {{-0.6f, -0.6f, 0.8f, 0.6f, 0.3f, 1.0f, 0.0f, 0.0f, 0.6f},   // nearest
                        {-0.8f, -0.4f, 0.6f, 0.8f, 0.7f, 0.0f, 0.0f, 1.0f, 0.6f},   // farthest
                        {-0.7f, -0.8f, 0.7f, 0.4f, 0.5f, 0.0f, 1.0f, 0.0f, 0.6f}};  // middle

const char* const kVertex = R"(#version 450 core
uniform vec4 rect;   // x0 y0 x1 y1
uniform float depth; // NDC z in [-1, 1]
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  gl_Position = vec4(mix(rect.xy, rect.zw, corner), depth, 1.0);
}
)";
const char* const kOpaqueFragment = R"(#version 450 core
uniform vec4 colour;
layout(location = 0) out vec4 out_colour;
void main() { out_colour = colour; }
)";
// The panes' gather shader: the module (it starts with #version), then ours.  // [habuffer]
const char* const kPaneMain = R"(                            // [habuffer]
layout(early_fragment_tests) in;                             // [habuffer]
uniform vec4 colour;                                         // [habuffer]
void main() { habuffer_insert_here(colour); }                      // [habuffer]
)";                                                          // [habuffer]

void draw(GLuint program, const Quad& q) {
  glUseProgram(program);
  glUniform4f(glGetUniformLocation(program, "rect"), q.x0, q.y0, q.x1, q.y1);
  glUniform1f(glGetUniformLocation(program, "depth"), 2.0f * q.depth - 1.0f);
  glUniform4f(glGetUniformLocation(program, "colour"), q.r, q.g, q.b, q.a);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

bool inside(const Quad& q, float x, float y) { return x >= q.x0 && x < q.x1 && y >= q.y0 && y < q.y1; }

// What pixel (px, py) must show: the panes in front of the opaque surface
// there, sorted near to far, blended front to back over it.
std::vector<float> expected_pixel(int px, int py) {
  const float x = (static_cast<float>(px) + 0.5f) / kWidth * 2.0f - 1.0f;
  const float y = (static_cast<float>(py) + 0.5f) / kHeight * 2.0f - 1.0f;
  const Quad& opaque = inside(kBox, x, y) ? kBox : kFloor;
  std::vector<const Quad*> panes;
  for (const Quad& q : kPanes)
    if (inside(q, x, y)) panes.push_back(&q);
  const std::array<double, 3> c = host_gl::blend_in_front(panes, opaque);
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

}  // namespace

int main() {
  try {
    host_gl::make_context();
    // The host's framebuffer, shaders and vertex array.
    const GLuint framebuffer = host_gl::make_framebuffer(kWidth, kHeight);
    GLuint vertex_array = 0;
    glCreateVertexArrays(1, &vertex_array);
    const GLuint opaque = link_program(kVertex, kOpaqueFragment);

    namespace hb = habuffer;                                                                  // [habuffer]
    const auto mode = hb::gl::chosen_atomic_mode(hb::gl::query_gl_info(), hb::Layout::L64);  // [habuffer]
    check(mode.has_value(), "this OpenGL has no 64-bit shader integers");                    // [habuffer]
    hb::BufferConfig config;                                                                  // [habuffer]
    config.screen = {kWidth, kHeight};                                                        // [habuffer]
    // No table given: the first frame is counted and sizes it, later frames adapt it (SPEC 8),
    // and a frame that drops anything is gathered again into a grown table (lossless).
    hb::gl::GlFrameOptions options;                                                           // [habuffer]
    hb::gl::GlHaBuffer oit(config, hb::OffsetSource{}, *mode, options);                      // [habuffer]
    const GLuint panes = link_program(kVertex, oit.module_source(hb::gl::ShaderStage::Fragment) + kPaneMain);  // [habuffer]

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glBindVertexArray(vertex_array);
    glViewport(0, 0, kWidth, kHeight);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    draw(opaque, kFloor);
    draw(opaque, kBox);
    // The translucent panes: depth tested against the opaque surfaces, no
    // depth writes, blended in submission order.
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the gather inserts, writes nothing  // [habuffer]
    const hb::gl::FrameReport report = oit.frame([&] {                                        // [habuffer]
      for (const Quad& q : kPanes) draw(panes, q);                                            // [habuffer]
    });                                                                                       // [habuffer]
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);                                          // [habuffer]
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    oit.resolve_over();  // the sorted panes over the opaque image                            // [habuffer]
    const hb::Counters& c = report.counters;                                                  // [habuffer]
    std::printf("habuffer: %llu fragments, %llu lost\n", (unsigned long long)c.fragments, (unsigned long long)c.failures());  // [habuffer]

    const int wrong = host_gl::count_wrong_channels(framebuffer, kWidth, kHeight, expected_pixel, "host_app");
    return wrong == 0 && c.failures() == 0 ? 0 : 1;  // [habuffer]
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_app: %s\n", e.what());
    return 1;
  }
}
