// Shadows from any light (issue 35, item 2): a host's light pass stores the
// depth the lookup compares, the light's linear t, through every route a
// driver told its light offers (habuffer_insert_light from gl_FragCoord.z or
// from the light's eye distance, habuffer_insert_here), for a spot, a
// point-at and a directional light in both depth conventions; the ground's
// shadows equal the transmittance computed on the CPU by casting each
// receiver's ray to the light through the panes, and each stored depth is
// within the documented codes of the exact t. The routes that would store
// something else are refused, each with one line.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_test_support.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/light_mapping.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/gl/shadow_lookup.h"

namespace habuffer {
namespace {

using test::gl_context;

constexpr std::uint32_t kMap = 64;        // the light map's side
constexpr double kDepthScale = 0x1.0p24;  // depth codes per unit of t (age bits 8)

// A horizontal rectangle x in [x0, x1], z in [z0, z1] at height y, with a
// straight-alpha colour.
struct Quad {
  float x0, z0, x1, z1, y;
  glm::vec4 colour;
};
const Quad kGround{-2.0f, -2.0f, 2.0f, 2.0f, 0.0f, {0.6f, 0.6f, 0.6f, 1.0f}};
const Quad kCasters[] = {{-1.2f, -1.0f, 0.4f, 1.0f, 1.0f, {1.0f, 0.0f, 0.0f, 0.5f}},
                         {-0.4f, -0.6f, 1.2f, 1.2f, 1.6f, {0.0f, 0.0f, 1.0f, 0.25f}},
                         {0.6f, -1.2f, 1.0f, -0.6f, 2.0f, {0.1f, 0.1f, 0.1f, 1.0f}}};

// A light: perspective from `position` at `target` (a spot looking straight
// down, or a point-at light looking aslant), or orthographic along
// target - position; `fov` in degrees (perspective) or the box's half side.
struct TestLight {
  const char* name;
  bool perspective;
  glm::vec3 position, target;
  float fov_or_half, near_plane, far_plane;
};
const TestLight kSpot{"spot", true, {0.0f, 5.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 2.5f, 5.5f};
const TestLight kPointAt{"point-at", true, {3.0f, 4.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 2.0f, 8.0f};
// The same spot with far / near 1000 and the ground near its far plane:
// window depth's float32 steps near 1 cost far / near times as much t there
// (code_bound).
const TestLight kDeepSpot{"deep spot", true, {0.0f, 5.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 0.0055f, 5.5f};
const TestLight kDirectional{"directional", false, {1.0f, 6.0f, 0.5f}, {0.0f, 0.0f, 0.0f}, 3.0f, 1.0f, 11.0f};

glm::vec3 up_for(const TestLight& l) {
  const glm::vec3 d = glm::normalize(l.target - l.position);
  return std::abs(d.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// Clip z of the reversed-Z projection: w - z of a zero-to-one one (near at 1).
glm::mat4 reversed_z(glm::mat4 p) {
  for (int c = 0; c < 4; ++c) p[c][2] = p[c][3] - p[c][2];
  return p;
}

// The light's mapping: glm's standard projection (clip depth -1..1), or a
// reversed-Z one (zero-to-one, near at window depth 1).
gl::GlLightMapping mapping_of(const TestLight& l, bool reversed) {
  gl::GlLightMapping m;
  m.view = glm::lookAt(l.position, l.target, up_for(l));
  const float n = l.near_plane, f = l.far_plane, h = l.fov_or_half;
  if (l.perspective)
    m.projection = reversed ? reversed_z(glm::perspectiveRH_ZO(glm::radians(h), 1.0f, n, f))
                            : glm::perspective(glm::radians(h), 1.0f, n, f);
  else
    m.projection = reversed ? reversed_z(glm::orthoRH_ZO(-h, h, -h, h, n, f)) : glm::ortho(-h, h, -h, h, n, f);
  m.near_plane = n;
  m.far_plane = f;
  return m;
}

// The world side of one light pixel at eye distance `d`.
double pixel_side(const TestLight& l, double d) {
  const double width = l.perspective ? 2.0 * d * std::tan(glm::radians(double{l.fov_or_half}) / 2.0)
                                     : 2.0 * double{l.fov_or_half};
  return width / kMap;
}

// The exact transmittance at ground point p, in double: the segment to the
// light (perspective) or the ray toward it (directional) through every
// caster, (1 - alpha8/255) each. Nullopt where the ray passes within two
// light pixels of a caster's edge, where the light pixel's lookup may
// differ from the exact ray.
std::optional<double> exact_transmittance(const TestLight& l, glm::dvec3 p) {
  const glm::dvec3 towards = l.perspective ? glm::dvec3(l.position) - p : glm::dvec3(l.position - l.target);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(l.target - l.position));
  double t = 1.0;
  for (const Quad& q : kCasters) {
    const double s = (double{q.y} - p.y) / towards.y;  // along `towards` to the caster's plane
    if (!(s > 0.0) || (l.perspective && s >= 1.0)) continue;
    const glm::dvec3 c = p + s * towards;
    const double margin = 2.0 * pixel_side(l, glm::dot(c - glm::dvec3(l.position), axis));
    const double inside = std::min({c.x - q.x0, q.x1 - c.x, c.z - q.z0, q.z1 - c.z});
    if (std::abs(inside) < margin) return std::nullopt;
    if (inside > 0.0) t *= 1.0 - std::round(double{q.colour.a} * 255.0) / 255.0;
  }
  return t;
}

// Ground points the light sees away from its map's border.
std::vector<glm::vec4> receivers(const TestLight& l, const gl::GlLightMapping& m) {
  std::vector<glm::vec4> out;
  const glm::dmat4 clip = glm::dmat4(m.projection) * glm::dmat4(m.view);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const glm::dvec4 p(-1.9 + 3.8 * (i + 0.5) / 40.0, 0.0, -1.9 + 3.8 * (j + 0.5) / 40.0, 1.0);
      const glm::dvec4 c = clip * p;
      const double border = 2.0 * 2.0 / kMap;  // two pixels in normalized device coordinates
      if (std::abs(c.x / c.w) < 1.0 - border && std::abs(c.y / c.w) < 1.0 - border && exact_transmittance(l, p))
        out.emplace_back(p.x, p.y, p.z, 1.0);
    }
  return out;
}

// The exact t of the ground where light pixel (x, y)'s centre ray meets it, in double.
std::optional<double> exact_ground_t(const TestLight& l, const gl::GlLightMapping& m, std::uint32_t x, std::uint32_t y) {
  const glm::dmat4 view(m.view), to_world = glm::inverse(view);
  const double nx = (x + 0.5) / kMap * 2.0 - 1.0, ny = (y + 0.5) / kMap * 2.0 - 1.0;
  const double ex = nx / m.projection[0][0], ey = ny / m.projection[1][1];
  const glm::dvec4 origin = to_world * (l.perspective ? glm::dvec4(0, 0, 0, 1) : glm::dvec4(ex, ey, 0, 1));
  const glm::dvec4 direction = to_world * (l.perspective ? glm::dvec4(ex, ey, -1, 0) : glm::dvec4(0, 0, -1, 0));
  const double s = -origin.y / direction.y;
  const glm::dvec4 p = origin + s * direction;
  if (!(std::abs(p.x) < 2.0 && std::abs(p.z) < 2.0)) return std::nullopt;
  const double d = -(view * glm::dvec4(p.x, 0.0, p.z, 1.0)).z;
  return (d - m.near_plane) / (double{m.far_plane} - m.near_plane);
}

constexpr const char* kCasterVertex = R"(#version 450 core
uniform vec4 rect;  // x0 z0 x1 z1
uniform float height;
uniform mat4 light_view;
uniform mat4 light_projection;
out float eye_distance;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  vec4 eye = light_view * vec4(mix(rect.x, rect.z, corner.x), height, mix(rect.y, rect.w, corner.y), 1.0);
  eye_distance = -eye.z;
  gl_Position = light_projection * eye;
}
)";
// The three routes of a driver told its light, chosen by `route`.
constexpr const char* kLightRoutes = R"(
in float eye_distance;
uniform vec4 colour;
uniform uint route;
void main() {
  if (route == 0u) habuffer_insert_light(colour);
  else if (route == 1u) habuffer_insert_light(colour, eye_distance);
  else habuffer_insert_here(colour);
}
)";
// The guide's route in a driver not told its light: window depth.
constexpr const char* kWindowRoute = R"(
uniform vec4 colour;
void main() { habuffer_insert_here(colour); }
)";
constexpr const char* kLookupMain = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 2) writeonly buffer LookupOut { float lookup_out[]; };
layout(std430, binding = 3) readonly buffer LookupIn { vec4 lookup_points[]; };
uniform uint lookup_count;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < lookup_count) lookup_out[i] = habuffer_shadow_transmittance(lookup_points[i].xyz);
}
)";

enum Route : unsigned { kInsertLight = 0, kInsertLightEye = 1, kInsertHere = 2 };
const char* route_name(unsigned r) {
  return r == kInsertLight ? "habuffer_insert_light(colour)"
                           : r == kInsertLightEye ? "habuffer_insert_light(colour, eye_distance)" : "habuffer_insert_here";
}

void set_matrix(GLuint program, const char* name, const glm::mat4& m) {
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(m));
}

// A light pass's GL state (a 64x64 framebuffer written nothing, a vertex
// array; a reversed-Z host's clip control and GL_GEQUAL, a standard one's
// GL_LEQUAL, both with depth writes off and no depth buffer, so every
// fragment passes), the context's defaults given back at the end.
class LightPassState {
 public:
  explicit LightPassState(bool reversed) {
    glCreateRenderbuffers(1, &renderbuffer_);
    glNamedRenderbufferStorage(renderbuffer_, GL_RGBA8, kMap, kMap);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferRenderbuffer(framebuffer_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer_);
    glCreateVertexArrays(1, &vertex_array_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    glBindVertexArray(vertex_array_);
    glViewport(0, 0, kMap, kMap);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(reversed ? GL_GEQUAL : GL_LEQUAL);
    glClipControl(GL_LOWER_LEFT, reversed ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
  }
  ~LightPassState() {
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glDeleteVertexArrays(1, &vertex_array_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteRenderbuffers(1, &renderbuffer_);
  }
  LightPassState(const LightPassState&) = delete;
  LightPassState& operator=(const LightPassState&) = delete;

 private:
  GLuint renderbuffer_ = 0, framebuffer_ = 0, vertex_array_ = 0;
};

gl::AtomicMode l64_mode() {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  return mode ? *mode : gl::AtomicMode::Native32;  // native32: the caller skips
}

// A light buffer of the map's side (room for every caster's fragment).
std::unique_ptr<gl::GlHaBuffer> light_buffer(std::optional<gl::GlLightMapping> light, bool reversed) {
  gl::GlFrameOptions o;
  o.max_attempts = 8;
  o.depth = reversed ? gl::DepthConvention::Reversed : gl::DepthConvention::Standard;
  o.light = std::move(light);
  return std::make_unique<gl::GlHaBuffer>(test::config({kMap, kMap}, {128, 128}, Layout::L64, 8), OffsetSource{},
                                          l64_mode(), o);
}

// Gathers the ground and the casters from the light with `program` (its
// `route` set first when given).
void gather(gl::GlHaBuffer& light, const gl::ShaderProgram& program, const gl::GlLightMapping& m,
            std::optional<unsigned> route) {
  const GLuint id = program.id();
  set_matrix(id, "light_view", m.view);
  set_matrix(id, "light_projection", m.projection);
  if (route) program.set("route", *route);
  const gl::FrameReport r = light.frame([&] {
    glUseProgram(id);
    for (const Quad& q : {kGround, kCasters[0], kCasters[1], kCasters[2]}) {
      glProgramUniform4f(id, glGetUniformLocation(id, "rect"), q.x0, q.z0, q.x1, q.z1);
      glProgramUniform1f(id, glGetUniformLocation(id, "height"), q.y);
      glProgramUniform4fv(id, glGetUniformLocation(id, "colour"), 1, glm::value_ptr(q.colour));
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
  });
  ASSERT_EQ(r.counters.failures(), 0u);
  ASSERT_EQ(r.counters.invalid, 0u);
  ASSERT_GT(r.counters.stored(), kMap * kMap / 2);
}

// T through `lookup` at every receiver, by a compute shader of the lookup's head.
std::vector<float> lookup_transmittance(gl::GlShadowLookup& lookup, const std::vector<glm::vec4>& points) {
  static std::optional<gl::ShaderProgram> program;  // one per process: compiling is slow on llvmpipe
  if (!program)
    program.emplace(gl::ShaderProgram::compute(gl::light_lookup_shader_head(lookup.bindings(), l64_mode()) + kLookupMain,
                                               "light lookup"));
  GLuint buffers[2] = {0, 0};
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(points.size() * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(points.size() * 16), points.data(), 0);
  lookup.bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers[1]);
  glUseProgram(program->id());
  program->set("lookup_count", static_cast<unsigned>(points.size()));
  glDispatchCompute(static_cast<GLuint>((points.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> out(points.size());
  glGetNamedBufferSubData(buffers[0], 0, static_cast<GLsizeiptr>(out.size() * 4), out.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
  glUseProgram(0);
  glDeleteBuffers(2, buffers);
  return out;
}

// The bias, 0.4 world units of eye distance in codes: between the ground's
// own depth over a light pixel (the point-at light's aslant ground moves by
// up to 0.17 across one) and the nearest caster above it (1 unit).
std::uint32_t bias_of(const TestLight& l) {
  return static_cast<std::uint32_t>(0.4 / (double{l.far_plane} - l.near_plane) * kDepthScale);
}

// Every receiver's T through `lookup` equals the exact transmittance.
void expect_exact_shadows(const TestLight& l, const gl::GlLightMapping& m, gl::GlShadowLookup& lookup) {
  const std::vector<glm::vec4> points = receivers(l, m);
  ASSERT_GT(points.size(), 600u);
  const std::vector<float> got = lookup_transmittance(lookup, points);
  int wrong = 0, shadowed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double want = *exact_transmittance(l, glm::dvec3(points[i]));
    shadowed += want < 1.0 ? 1 : 0;
    if (std::abs(double{got[i]} - want) > 1e-6 && ++wrong <= 5)
      ADD_FAILURE() << "ground (" << points[i].x << ", " << points[i].z << "): T " << got[i] << ", exact " << want;
  }
  EXPECT_EQ(wrong, 0) << "of " << points.size() << " receivers";
  EXPECT_GT(shadowed, static_cast<int>(points.size() / 8));
}

// The rasterizer's share of a record's error, in codes: it snaps each
// vertex to its subpixel grid (GL_SUBPIXEL_BITS), so the plane it
// interpolates is the exact one moved by up to half a subpixel step; at a
// pixel where t changes by `slope` codes a pixel, that is slope / 2^bits
// (an NVIDIA GPU's steep ground: 17 and 457 codes measured, issue 46).
double snapping_codes(double slope) {
  GLint bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
  return slope / std::ldexp(1.0, std::clamp(bits, 1, 16));
}

// The largest excess, in depth codes, of a stored ground record's distance
// from the exact t of the ground at its light pixel's centre over what the
// rasterizer's snapping allows there (snapping_codes of t's steepest step to
// a neighbouring pixel): what code_bound bounds.
std::uint32_t ground_code_error(const gl::GlHaBuffer& light, const TestLight& l, const gl::GlLightMapping& m) {
  const std::unique_ptr<FragmentBuffer> cpu = light.technique().read_back();
  const RecordLayout layout(Layout::L64, 8);
  const glm::vec4 g = kGround.colour;
  const std::uint32_t ground = (static_cast<std::uint32_t>(std::lround(g.r * 255.0f)) << 24) |
                               (static_cast<std::uint32_t>(std::lround(g.g * 255.0f)) << 16) |
                               (static_cast<std::uint32_t>(std::lround(g.b * 255.0f)) << 8) |
                               static_cast<std::uint32_t>(std::lround(g.a * 255.0f));
  std::vector<ListEntry> list;
  std::uint32_t worst = 0, seen = 0;
  for (std::uint32_t y = 0; y < kMap; ++y)
    for (std::uint32_t x = 0; x < kMap; ++x) {
      const std::optional<double> t = exact_ground_t(l, m, x, y);
      cpu->list(x, y, list);
      const auto it = std::find_if(list.begin(), list.end(), [&](const ListEntry& e) { return e.data == ground; });
      if (!t || it == list.end() || *t <= 0.0 || *t >= 1.0) continue;
      ++seen;
      const auto exact = static_cast<std::int64_t>(layout.max_code()) - static_cast<std::int64_t>(std::floor(*t * kDepthScale));
      double slope = 0.0;  // codes a pixel, to the steepest neighbour on the ground
      for (const glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
        const int nx = static_cast<int>(x) + d.x, ny = static_cast<int>(y) + d.y;
        if (nx < 0 || ny < 0 || nx >= static_cast<int>(kMap) || ny >= static_cast<int>(kMap)) continue;
        if (const std::optional<double> n = exact_ground_t(l, m, static_cast<std::uint32_t>(nx), static_cast<std::uint32_t>(ny)))
          slope = std::max(slope, std::abs(*n - *t) * kDepthScale);
      }
      const double error = static_cast<double>(std::llabs(exact - std::int64_t{it->code})) - snapping_codes(slope);
      worst = std::max(worst, static_cast<std::uint32_t>(std::max(0.0, std::ceil(error))));
    }
  EXPECT_GT(seen, kMap * kMap / 4);
  return worst;
}

// The precision bounds of docs/embedding.md 8a, in depth codes (24 bits):
// from the eye distance, 2^-21 of (far / (far - near)); from window depth,
// 2^-21 of far / near under a perspective light (the window depth's
// float32 steps near 1 stretched by the projection) and 2^-21 under an
// orthographic one, each plus one code for quantization.
std::uint32_t code_bound(const TestLight& l, unsigned route) {
  const double n = l.near_plane, f = l.far_plane;
  const double scale = route == kInsertLightEye ? f / (f - n) : (l.perspective ? f / n : 1.0);
  return static_cast<std::uint32_t>(std::ceil(8.0 * scale)) + 1u;
}

// Every route of a driver told its light, and the window route where the
// light's t is window depth (orthographic), in both conventions.
void check_light(const TestLight& l) {
  gl_context();
  if (l64_mode() == gl::AtomicMode::Native32) GTEST_SKIP() << "no 64-bit shader integers: no L64 light buffer";
  for (const bool reversed : {false, true}) {
    SCOPED_TRACE(std::string(l.name) + (reversed ? ", reversed-Z" : ", standard depth"));
    const LightPassState state(reversed);
    const gl::GlLightMapping m = mapping_of(l, reversed);
    const std::unique_ptr<gl::GlHaBuffer> light = light_buffer(m, reversed);
    const gl::ShaderProgram program = gl::ShaderProgram::graphics(
        kCasterVertex, light->module_source(gl::ShaderStage::Fragment) + kLightRoutes, "light pass");
    gl::GlShadowLookup lookup(light->container(), m, bias_of(l));
    std::vector<std::uint64_t> here_table;
    for (const unsigned route : {kInsertLight, kInsertLightEye, kInsertHere}) {
      SCOPED_TRACE(route_name(route));
      gather(*light, program, m, route);
      expect_exact_shadows(l, m, lookup);
      const std::uint32_t error = ground_code_error(*light, l, m);
      std::printf("[ precision ] %s%s %s: ground records within %u codes (beyond snapping) of the exact t (bound %u)\n", l.name,
                  reversed ? " reversed-Z" : "", route_name(route), error, code_bound(l, route));
      EXPECT_LE(error, code_bound(l, route));
      if (route == kInsertLight) here_table = light->read_table();
      if (route == kInsertHere) {
        EXPECT_TRUE(light->read_table() == here_table) << "insert_here stores insert_light's t";
      }
    }
    const std::unique_ptr<gl::GlHaBuffer> window = light_buffer(std::nullopt, reversed);
    const gl::ShaderProgram window_program = gl::ShaderProgram::graphics(
        kCasterVertex, window->module_source(gl::ShaderStage::Fragment) + kWindowRoute, "window-depth light pass");
    gather(*window, window_program, m, std::nullopt);
    if (l.perspective) {
      try {
        gl::GlShadowLookup refused(window->container(), m, bias_of(l));
        ADD_FAILURE() << "a perspective light's lookup of window depth was accepted";
      } catch (const gl::GlError& e) {
        EXPECT_NE(std::string(e.what()).find("window depth"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      }
    } else {
      gl::GlShadowLookup window_lookup(window->container(), m, bias_of(l));  // orthographic: window depth is t
      expect_exact_shadows(l, m, window_lookup);
    }
  }
}

TEST(GlLightRoutes, ASpotLightShadowsExactlyThroughEveryLightRouteInBothDepthConventions) { check_light(kSpot); }

TEST(GlLightRoutes, APointAtLightShadowsExactlyThroughEveryLightRouteInBothDepthConventions) { check_light(kPointAt); }

TEST(GlLightRoutes, ASpotLightOfFarOverNearThousandStaysWithinTheDocumentedPrecisionOnEveryRoute) {
  check_light(kDeepSpot);
}

TEST(GlLightRoutes, ADirectionalLightShadowsExactlyThroughEveryLightRouteAndThroughWindowDepth) {
  check_light(kDirectional);
}

// A perspective projection with no far plane, clip depth 0 at `near` and 1 at infinity.
glm::mat4 infinite_zero_to_one(float near_plane) {
  glm::mat4 p = glm::perspectiveRH_ZO(1.0f, 1.0f, near_plane, 2.0f * near_plane);
  p[2][2] = -1.0f;
  p[3][2] = -near_plane;
  return p;
}

// The map inverts the projection and window mapping: t of the window depth
// of eye distance e is (e - near) / (far - near), for perspective and
// orthographic projections, both clip conventions, reversed-Z, an infinite
// far plane and a depth range other than [0, 1].
TEST(GlLightRoutes, TheDepthMapInvertsEveryProjectionAndWindowMappingToLinearT) {
  struct Case {
    const char* name;
    glm::mat4 projection;
    gl::GlWindowDepth window;
  };
  const float n = 0.5f, f = 40.0f;
  const Case cases[] = {
      {"perspective", glm::perspective(1.0f, 1.0f, n, f), {}},
      {"perspective, zero-to-one", glm::perspectiveRH_ZO(1.0f, 1.0f, n, f), {true, 0.0f, 1.0f}},
      {"reversed-Z", reversed_z(glm::perspectiveRH_ZO(1.0f, 1.0f, n, f)), {true, 0.0f, 1.0f}},
      {"reversed-Z, infinite far", reversed_z(infinite_zero_to_one(n)), {true, 0.0f, 1.0f}},
      {"orthographic", glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, n, f), {}},
      {"orthographic, depth range 0.25..0.75", glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, n, f), {false, 0.25f, 0.75f}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    gl::GlLightMapping m;
    m.projection = c.projection;
    m.near_plane = n;
    m.far_plane = f;
    const gl::GlLightDepthMap map = gl::light_depth_map(m, c.window);
    for (const double t : {0.0, 0.1, 0.5, 0.9, 1.0}) {
      const double e = n + t * (f - n);
      const glm::dvec4 clip = glm::dmat4(c.projection) * glm::dvec4(0.0, 0.0, -e, 1.0);
      const double ndc = clip.z / clip.w;
      const double s = c.window.zero_to_one ? ndc : 0.5 * ndc + 0.5;
      const double z = c.window.range_near + (double{c.window.range_far} - c.window.range_near) * s;
      EXPECT_NEAR(map(static_cast<float>(z)), t, 2e-4) << "t " << t;  // float32 z near 1 under far / near = 80
    }
  }
  gl::GlLightMapping oblique;
  oblique.projection[0][2] = 0.1f;
  EXPECT_THROW((void)gl::light_depth_map(oblique, {}), std::invalid_argument);
  gl::GlLightMapping inverted;
  inverted.near_plane = 2.0f;
  inverted.far_plane = 1.0f;
  EXPECT_THROW((void)gl::light_depth_map(inverted, {}), std::invalid_argument);
  EXPECT_THROW((void)gl::light_depth_map({}, {false, 0.5f, 0.5f}), gl::GlError);
}

// The wrong routes, each one line: habuffer_insert_light in a driver not
// told its light does not compile; a lookup made before the gather refuses
// window depth under a perspective light at bind(); a lookup of another
// light than the driver's is refused until set_light moves the driver's;
// set_light on a driver without a light and a light the map refuses throw.
TEST(GlLightRoutes, EveryRouteThatWouldStoreAnotherDepthIsRefusedInOneLine) {
  gl_context();
  if (l64_mode() == gl::AtomicMode::Native32) GTEST_SKIP() << "no 64-bit shader integers: no L64 light buffer";
  const LightPassState state(false);
  const gl::GlLightMapping spot = mapping_of(kSpot, false);
  const auto one_line = [](const std::exception& e) { return std::string(e.what()).find('\n') == std::string::npos; };

  const std::unique_ptr<gl::GlHaBuffer> window = light_buffer(std::nullopt, false);
  try {
    (void)gl::ShaderProgram::graphics(kCasterVertex,
                                      window->module_source(gl::ShaderStage::Fragment) + kLightRoutes, "light pass");
    ADD_FAILURE() << "habuffer_insert_light compiled in a driver without GlFrameOptions::light";
  } catch (const gl::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("habuffer_insert_light_needs_GlFrameOptions_light"), std::string::npos)
        << e.what();
  }
  gl::GlShadowLookup early(window->container(), spot, bias_of(kSpot));  // nothing gathered yet: nothing to check
  const gl::ShaderProgram window_program = gl::ShaderProgram::graphics(
      kCasterVertex, window->module_source(gl::ShaderStage::Fragment) + kWindowRoute, "window-depth light pass");
  gather(*window, window_program, spot, std::nullopt);
  try {
    early.bind();
    ADD_FAILURE() << "bind() accepted window depth under a spot light";
  } catch (const gl::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("GlFrameOptions::light"), std::string::npos) << e.what();
    EXPECT_TRUE(one_line(e)) << e.what();
  }

  const std::unique_ptr<gl::GlHaBuffer> light = light_buffer(spot, false);
  const gl::ShaderProgram program = gl::ShaderProgram::graphics(
      kCasterVertex, light->module_source(gl::ShaderStage::Fragment) + kLightRoutes, "light pass");
  gather(*light, program, spot, kInsertLight);
  const gl::GlLightMapping moved = mapping_of(kPointAt, false);
  try {
    gl::GlShadowLookup other(light->container(), moved, bias_of(kPointAt));
    ADD_FAILURE() << "a lookup of another light than the driver's was accepted";
  } catch (const gl::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("another light"), std::string::npos) << e.what();
    EXPECT_TRUE(one_line(e)) << e.what();
  }
  light->set_light(moved);
  gather(*light, program, moved, kInsertLight);
  gl::GlShadowLookup following(light->container(), moved, bias_of(kPointAt));
  expect_exact_shadows(kPointAt, moved, following);

  EXPECT_THROW(window->set_light(spot), std::invalid_argument);
  gl::GlLightMapping oblique = spot;
  oblique.projection[1][3] = 0.5f;
  EXPECT_THROW(light->set_light(oblique), std::invalid_argument);
  gl::GlFrameOptions bad;
  bad.light = oblique;
  EXPECT_THROW((void)gl::GlHaBuffer(test::config({kMap, kMap}, {kMap, kMap}), OffsetSource{}, l64_mode(), bad),
               std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
