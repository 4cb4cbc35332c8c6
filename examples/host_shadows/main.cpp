// Translucent shadows in a host OpenGL app (seed 000, section 6): the app
// draws an opaque floor and an opaque box under three translucent panes and
// wants the light the panes take away from what lies below them (the panes
// themselves are left out of the view to keep the check to the shadows:
// host_app composites them). habuffer
// gives it through the lines that end in the habuffer tag: a light buffer
// (an HA-buffer of every caster seen from the light, gathered once), the
// lookup's GLSL appended to the app's opaque shader (the installed
// light_lookup.glsl holds the same), and one call per fragment:
//
//   colour *= habuffer_shadow_transmittance(world_point);
//
// The light here shines straight down the view's axis (orthographic, its
// matrices given to GlShadowLookup as a host with its own light would), so
// the expected image is short to compute by hand: each opaque pixel's colour
// times the product of (1 - alpha8/255) over the panes above it, and the box
// (in front of every pane) unshadowed, its own record excluded by the bias.
//
// Exits 0 when every pixel matches (within 1.5/255), 1 otherwise.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "../host_gl.h"
#include <glm/gtc/matrix_transform.hpp>

#include <habuffer/gl.h>  // [habuffer]

namespace {

using host_gl::check;
using host_gl::link_program;

constexpr int kWidth = 160, kHeight = 120;

// An axis-aligned rectangle of the world's x, y in [-1, 1] at depth z in
// [0, 1] (0 nearest the light and the eye), with a straight-alpha colour.
struct Quad {
  float x0, y0, x1, y1, depth;
  float r, g, b, a;
};
const Quad kFloor{-1.0f, -1.0f, 1.0f, 1.0f, 0.9f, 0.8f, 0.8f, 0.8f, 1.0f};
const Quad kBox{0.5f, -0.5f, 0.9f, 0.5f, 0.1f, 0.9f, 0.9f, 0.1f, 1.0f};
const Quad kPanes[3] = {{-0.6f, -0.6f, 0.8f, 0.6f, 0.3f, 1.0f, 0.0f, 0.0f, 0.6f},
                        {-0.8f, -0.4f, 0.6f, 0.8f, 0.7f, 0.0f, 0.0f, 1.0f, 0.25f},
                        {-0.7f, -0.8f, 0.7f, 0.4f, 0.5f, 0.0f, 1.0f, 0.0f, 0.5f}};

// The world point of a rectangle's corner, drawn by the view (and the light)
// in normalized device coordinates: x, y as they are, z = 2 depth - 1.
const char* const kVertex = R"(#version 450 core
uniform vec4 rect;    // x0 y0 x1 y1
uniform float depth;  // in [0, 1]
out vec3 world;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  world = vec3(mix(rect.xy, rect.zw, corner), depth);
  gl_Position = vec4(world.xy, 2.0 * depth - 1.0, 1.0);
}
)";
// The app's opaque shader, lit by the light's transmittance.
const char* const kOpaqueMain = R"(
in vec3 world;
uniform vec4 colour;
layout(location = 0) out vec4 out_colour;
void main() {
  float t = habuffer_shadow_transmittance(world);  // [habuffer]
  out_colour = vec4(colour.rgb * t, 1.0);
}
)";
// The casters seen from the light: every quad inserted with its opacity.  // [habuffer]
const char* const kCasterMain = R"(                                           // [habuffer]
uniform vec4 colour;                                                          // [habuffer]
void main() { habuffer_insert_here(colour); }                                 // [habuffer]
)";                                                                           // [habuffer]

void draw(GLuint program, const Quad& q) {
  glUseProgram(program);
  glUniform4f(glGetUniformLocation(program, "rect"), q.x0, q.y0, q.x1, q.y1);
  glUniform1f(glGetUniformLocation(program, "depth"), q.depth);
  glUniform4f(glGetUniformLocation(program, "colour"), q.r, q.g, q.b, q.a);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

bool inside(const Quad& q, float x, float y) { return x >= q.x0 && x < q.x1 && y >= q.y0 && y < q.y1; }

// What pixel (px, py) must show: the opaque surface there, times the
// product of (1 - alpha8/255) over the panes in front of it.
std::vector<float> expected_pixel(int px, int py) {
  const float x = (static_cast<float>(px) + 0.5f) / kWidth * 2.0f - 1.0f;
  const float y = (static_cast<float>(py) + 0.5f) / kHeight * 2.0f - 1.0f;
  const Quad& opaque = inside(kBox, x, y) ? kBox : kFloor;
  float t = 1.0f;
  for (const Quad& q : kPanes)
    if (inside(q, x, y) && q.depth < opaque.depth) t *= 1.0f - std::round(q.a * 255.0f) / 255.0f;
  return {opaque.r * t, opaque.g * t, opaque.b * t};
}

}  // namespace

int main() {
  try {
    host_gl::make_context();
    const GLuint framebuffer = host_gl::make_framebuffer(kWidth, kHeight);
    GLuint vertex_array = 0;
    glCreateVertexArrays(1, &vertex_array);
    glBindVertexArray(vertex_array);

    namespace hb = habuffer;                                                                  // [habuffer]
    const auto mode = hb::gl::chosen_atomic_mode(hb::gl::query_gl_info(), hb::Layout::L64);  // [habuffer]
    check(mode.has_value(), "this OpenGL has no 64-bit shader integers");                    // [habuffer]
    // The light buffer: the light's map (here the view's pixels), L64 records.              // [habuffer]
    hb::BufferConfig config;                                                                  // [habuffer]
    config.screen = {kWidth, kHeight};                                                        // [habuffer]
    hb::gl::GlFrameOptions options;                                                           // [habuffer]
    options.adaptive = true;   // the table follows the casters' fragments                    // [habuffer]
    options.max_attempts = 16;  // a gather that drops anything is redone larger              // [habuffer]
    hb::gl::GlHaBuffer light(config, hb::OffsetSource{}, *mode, options);                    // [habuffer]
    const GLuint casters = link_program(kVertex, light.module_source(hb::gl::ShaderStage::Fragment) + kCasterMain);  // [habuffer]
    // Gathered once (again only when the light moves): every quad, opaque ones at alpha 1,  // [habuffer]
    // into any framebuffer of the map's size (the app's own, nothing written).             // [habuffer]
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);                                      // [habuffer]
    glViewport(0, 0, kWidth, kHeight);                                                        // [habuffer]
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);                                      // [habuffer]
    const hb::gl::FrameReport built = light.frame([&] {                                      // [habuffer]
      for (const Quad& q : {kFloor, kBox, kPanes[0], kPanes[1], kPanes[2]}) draw(casters, q); // [habuffer]
    });                                                                                       // [habuffer]
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);                                          // [habuffer]
    // The light's matrices: world z is depth along -z of its eye, an orthographic box.     // [habuffer]
    hb::gl::GlLightMapping mapping;                                                           // [habuffer]
    mapping.view = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, -1.0f));               // [habuffer]
    mapping.projection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.0f, 1.0f);                  // [habuffer]
    mapping.near_plane = 0.0f;                                                                // [habuffer]
    mapping.far_plane = 1.0f;                                                                 // [habuffer]
    // Bias 2 codes: the light's depth (the rasterizer's window z) and the mapping's          // [habuffer]
    // (the matrices') may round a code apart on a surface facing the light.                 // [habuffer]
    hb::gl::GlShadowLookup lookup(light.container(), mapping, 2);                            // [habuffer]
    const std::string head = hb::gl::light_lookup_shader_head(lookup.bindings(), *mode);     // [habuffer]
    const GLuint opaque = link_program(kVertex, head + kOpaqueMain);

    // The app's frame: its opaque surfaces, depth-tested, lit by the light buffer.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    lookup.bind();  // the light buffer and its block, at points of their own                // [habuffer]
    draw(opaque, kFloor);
    draw(opaque, kBox);
    glDisable(GL_DEPTH_TEST);
    const hb::Counters& c = built.counters;                                                   // [habuffer]
    std::printf("habuffer: light buffer of %llu fragments, %llu lost\n", (unsigned long long)c.fragments,  // [habuffer]
                (unsigned long long)c.failures());                                            // [habuffer]

    const int wrong = host_gl::count_wrong_channels(framebuffer, kWidth, kHeight, expected_pixel, "host_shadows");
    return wrong == 0 && c.failures() == 0 ? 0 : 1;  // [habuffer]
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_shadows: %s\n", e.what());
    return 1;
  }
}
