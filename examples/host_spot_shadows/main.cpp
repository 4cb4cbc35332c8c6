// Translucent shadows from a spot light in a host OpenGL app (seed 000,
// section 6; issue 35): host_shadows with a perspective light. A spot
// light above and to the side of an opaque floor shines through three
// translucent panes and an opaque tile; the app looks straight down at the
// floor and shades it by the light's transmittance:
//
//   colour *= habuffer_shadow_transmittance(world_point);
//
// A perspective light's window depth (gl_FragCoord.z) is not the depth the
// lookup compares (t, linear in the light's eye distance), so the light's
// driver is told its light (GlFrameOptions::light) and the light pass
// inserts with habuffer_insert_light(colour), which stores t. (The guide's
// habuffer_insert_here stores t too in such a driver; in a driver not told
// its light, the lookup refuses the buffer under a perspective light.)
//
// The check computes each floor pixel by hand: the floor's colour times the
// product of (1 - alpha8/255) over the casters that the segment from the
// floor point to the light crosses. Pixels whose segment passes within one
// light pixel of a caster's edge are left out (the light map's pixels decide
// there: a pixel's centre lies up to 0.71 of its side from the segment).
// Exits 0 when every other pixel matches (within 1.5/255) and the edge band
// is under a tenth of the image.
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
#include <glm/gtc/type_ptr.hpp>

#include <habuffer/gl.h>  // [habuffer]

namespace {

using host_gl::check;
using host_gl::link_program;

constexpr int kSize = 128;      // the view's pixels (square)
constexpr int kLightMap = 512;  // the light map's pixels (square)

// A horizontal rectangle x in [x0, x1], z in [z0, z1] at height y, with a
// straight-alpha colour.
struct Quad {
  float x0, z0, x1, z1, y;
  float r, g, b, a;
};
const Quad kFloor{-1.0f, -1.0f, 1.0f, 1.0f, 0.0f, 0.8f, 0.8f, 0.8f, 1.0f};
const Quad kCasters[4] = {{-0.7f, -0.5f, 0.3f, 0.5f, 0.8f, 1.0f, 0.0f, 0.0f, 0.6f},
                          {-0.3f, -0.8f, 0.6f, 0.1f, 0.5f, 0.0f, 0.0f, 1.0f, 0.25f},
                          {-0.5f, 0.0f, 0.4f, 0.8f, 0.3f, 0.0f, 1.0f, 0.0f, 0.5f},
                          {0.45f, 0.3f, 0.75f, 0.6f, 0.6f, 0.2f, 0.2f, 0.2f, 1.0f}};

// The spot: at kLightPosition, looking at the floor's centre, a 60-degree cone.
const glm::vec3 kLightPosition{0.6f, 3.0f, 0.8f};
constexpr float kFov = 60.0f, kNear = 1.0f, kFar = 4.5f;

// A rectangle's world points; drawn through `to_clip` (the view's or the
// light's matrices), with the light's eye distance for the light pass.
const char* const kVertex = R"(#version 450 core
uniform vec4 rect;  // x0 z0 x1 z1
uniform float height;
uniform mat4 to_clip;
out vec3 world;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  world = vec3(mix(rect.x, rect.z, corner.x), height, mix(rect.y, rect.w, corner.y));
  gl_Position = to_clip * vec4(world, 1.0);
}
)";
// The app's floor shader, lit by the light's transmittance.
const char* const kFloorMain = R"(
in vec3 world;
uniform vec4 colour;
layout(location = 0) out vec4 out_colour;
void main() {
  float t = habuffer_shadow_transmittance(world);  // [habuffer]
  out_colour = vec4(colour.rgb * t, 1.0);
}
)";
// The casters seen from the light, at the light's depth t.                   // [habuffer]
const char* const kCasterMain = R"(                                           // [habuffer]
uniform vec4 colour;                                                          // [habuffer]
void main() { habuffer_insert_light(colour); }                                // [habuffer]
)";                                                                           // [habuffer]

void draw(GLuint program, const Quad& q, const glm::mat4& to_clip) {
  glUseProgram(program);
  glUniform4f(glGetUniformLocation(program, "rect"), q.x0, q.z0, q.x1, q.z1);
  glUniform1f(glGetUniformLocation(program, "height"), q.y);
  glUniform4f(glGetUniformLocation(program, "colour"), q.r, q.g, q.b, q.a);
  glUniformMatrix4fv(glGetUniformLocation(program, "to_clip"), 1, GL_FALSE, glm::value_ptr(to_clip));
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

// The world side of one light pixel at eye distance d.
double light_pixel(double d) { return 2.0 * d * std::tan(glm::radians(double{kFov}) / 2.0) / kLightMap; }

// The floor point a view pixel shows (the view looks straight down on it).
glm::dvec3 floor_point(int px, int py) {
  return {-1.0 + 2.0 * (px + 0.5) / kSize, 0.0, 1.0 - 2.0 * (py + 0.5) / kSize};
}

// The transmittance at floor point p by hand: the segment to the light
// through each caster; false near a caster's edge (within one light pixel).
bool transmittance_by_hand(glm::dvec3 p, double& t) {
  const glm::dvec3 light(kLightPosition), axis = glm::normalize(-light);
  t = 1.0;
  for (const Quad& q : kCasters) {
    const double s = q.y / light.y;  // the caster's plane along the segment
    const glm::dvec3 c = p + s * (light - p);
    const double inside = std::min({c.x - q.x0, q.x1 - c.x, c.z - q.z0, q.z1 - c.z});
    if (std::abs(inside) < light_pixel(glm::dot(c - light, axis))) return false;
    if (inside > 0.0) t *= 1.0 - std::round(q.a * 255.0) / 255.0;
  }
  return true;
}

}  // namespace

int main() {
  try {
    host_gl::make_context();
    const GLuint framebuffer = host_gl::make_framebuffer(kSize, kSize);
    const GLuint light_framebuffer = host_gl::make_framebuffer(kLightMap, kLightMap);
    GLuint vertex_array = 0;
    glCreateVertexArrays(1, &vertex_array);
    glBindVertexArray(vertex_array);

    namespace hb = habuffer;                                                                  // [habuffer]
    const auto mode = hb::gl::chosen_atomic_mode(hb::gl::query_gl_info(), hb::Layout::L64);  // [habuffer]
    check(mode.has_value(), "this OpenGL has no 64-bit shader integers");                    // [habuffer]
    // The spot's matrices, and the eye distances of the lookup's t = 0 and 1.               // [habuffer]
    hb::gl::GlLightMapping light;                                                             // [habuffer]
    light.view = glm::lookAt(kLightPosition, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));  // [habuffer]
    light.projection = glm::perspective(glm::radians(kFov), 1.0f, kNear, kFar);             // [habuffer]
    light.near_plane = kNear;                                                                 // [habuffer]
    light.far_plane = kFar;                                                                   // [habuffer]
    // The light buffer: the light's map, L64 records, its driver told the light.            // [habuffer]
    hb::BufferConfig config;                                                                  // [habuffer]
    config.screen = {kLightMap, kLightMap};                                                   // [habuffer]
    hb::gl::GlFrameOptions options;                                                           // [habuffer]
    options.adaptive = true;                                                                  // [habuffer]
    options.max_attempts = 16;                                                                // [habuffer]
    options.light = light;  // the records hold the light's t                                 // [habuffer]
    hb::gl::GlHaBuffer light_buffer(config, hb::OffsetSource{}, *mode, options);             // [habuffer]
    const GLuint casters = link_program(kVertex, light_buffer.module_source(hb::gl::ShaderStage::Fragment) + kCasterMain);  // [habuffer]
    // Gathered once (again only when the light moves: set_light): every quad, opaque    // [habuffer]
    // ones at alpha 1, into a framebuffer of the map's size (nothing written).             // [habuffer]
    const glm::mat4 light_clip = light.projection * light.view;                               // [habuffer]
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, light_framebuffer);                                // [habuffer]
    glViewport(0, 0, kLightMap, kLightMap);                                                   // [habuffer]
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);                                      // [habuffer]
    const hb::gl::FrameReport built = light_buffer.frame([&] {                               // [habuffer]
      for (const Quad& q : {kFloor, kCasters[0], kCasters[1], kCasters[2], kCasters[3]}) draw(casters, q, light_clip);  // [habuffer]
    });                                                                                       // [habuffer]
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);                                          // [habuffer]
    // The bias: a surface 2 light pixels deep per pixel of side (slope 2) at the far         // [habuffer]
    // plane, in depth codes (24 bits), so the floor's own records never shadow it.           // [habuffer]
    const double side = 2.0 * kFar * std::tan(glm::radians(double{kFov}) / 2.0) / kLightMap;  // [habuffer]
    const auto bias = static_cast<std::uint32_t>(2.0 * side / (kFar - kNear) * 0x1.0p24) + 1;  // [habuffer]
    hb::gl::GlShadowLookup lookup(light_buffer.container(), light, bias);                    // [habuffer]
    const std::string head = hb::gl::light_lookup_shader_head(lookup.bindings(), *mode);     // [habuffer]
    const GLuint floor = link_program(kVertex, head + kFloorMain);

    // The app's frame: the floor seen from straight above, lit by the light buffer.
    const glm::mat4 view_clip = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.0f, 4.0f) *
                                glm::lookAt(glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, kSize, kSize);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    lookup.bind();  // the light buffer and its block, at points of their own                // [habuffer]
    draw(floor, kFloor, view_clip);
    const hb::Counters& c = built.counters;                                                   // [habuffer]
    std::printf("habuffer: light buffer of %llu fragments, %llu lost\n", (unsigned long long)c.fragments,  // [habuffer]
                (unsigned long long)c.failures());                                            // [habuffer]

    // Pixels of the edge band expect -1: left unchecked, counted apart.
    int band = 0;
    const auto expected = [&](int px, int py) {
      double t = 1.0;
      if (!transmittance_by_hand(floor_point(px, py), t)) {
        ++band;
        return std::vector<float>{-1.0f, -1.0f, -1.0f};
      }
      const auto v = static_cast<float>(kFloor.r * t);
      return std::vector<float>{v, v, v};
    };
    const int wrong = host_gl::count_wrong_channels(framebuffer, kSize, kSize, expected, "host_spot_shadows");
    std::printf("host_spot_shadows: %d of %d pixels on casters' edges left out\n", band, kSize * kSize);
    return wrong == 0 && band < kSize * kSize / 10 && c.failures() == 0 ? 0 : 1;  // [habuffer]
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_spot_shadows: %s\n", e.what());
    return 1;
  }
}
