#include "habuffer/render/csg_renderer.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gpu_triangles.h"
#include "record_gather.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/light_view.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

const char* const kVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 view;
uniform mat4 projection;
out vec3 v_eye;
void main() {
  vec4 eye = view * vec4(position, 1.0);
  v_eye = eye.xyz;
  gl_Position = projection * eye;
}
)";
const char* const kCrossing = R"(
in vec3 v_eye;
uniform float near_plane;
uniform float far_plane;
uniform uint primitive;
void main() {
  float t = (-v_eye.z - near_plane) / (far_plane - near_plane);
  habuffer_insert(uvec2(gl_FragCoord.xy), clamp(t, 0.0, 1.0), (primitive << 1u) | (gl_FrontFacing ? 0u : 1u));
}
)";

// A flat-ish shade of primitive `id` (a colour per id) lit by the surface's
// normal from the depth image: the positions of the neighbouring pixels.
glm::vec3 palette(std::int32_t id) {
  const float h = std::fmod(static_cast<float>(id) * 0.618034f, 1.0f);
  return glm::vec3(0.55f + 0.4f * std::cos(6.2832f * h), 0.55f + 0.4f * std::cos(6.2832f * (h - 0.333f)),
                   0.55f + 0.4f * std::cos(6.2832f * (h - 0.667f)));
}

void shade(CsgRender& r, const RecordLayout& layout, Extent screen) {
  std::vector<glm::dvec3> eye(screen.area(), glm::dvec3(0.0));
  const glm::dmat4 view(r.camera.view);
  for (std::size_t i = 0; i < screen.area(); ++i)
    if (r.primitive[i] >= 0) {
      const double t = (static_cast<double>(layout.max_code() - r.codes[i]) + 0.5) / std::ldexp(1.0, static_cast<int>(layout.depth_bits()));
      const glm::dvec3 w = unproject(r.camera, screen, {static_cast<double>(i % screen.x) + 0.5, static_cast<double>(i / screen.x) + 0.5}, t);
      eye[i] = glm::dvec3(view * glm::dvec4(w, 1.0));
    }
  r.image = Image{screen, std::vector<glm::vec4>(screen.area(), glm::vec4(1.0f))};
  const auto at = [&](std::int64_t x, std::int64_t y, std::size_t fallback) {
    if (x < 0 || y < 0 || x >= screen.x || y >= screen.y) return fallback;
    const std::size_t j = static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * screen.x;
    return r.primitive[j] >= 0 ? j : fallback;
  };
  for (std::size_t i = 0; i < screen.area(); ++i) {
    if (r.primitive[i] < 0) continue;
    const std::int64_t x = static_cast<std::int64_t>(i % screen.x), y = static_cast<std::int64_t>(i / screen.x);
    const glm::dvec3 dx = eye[at(x + 1, y, i)] - eye[at(x - 1, y, i)], dy = eye[at(x, y + 1, i)] - eye[at(x, y - 1, i)];
    const glm::dvec3 n = glm::cross(dx, dy);
    const double len = glm::length(n);
    const float facing = len > 0.0 ? static_cast<float>(std::abs(n.z) / len) : 1.0f;
    r.image.pixels[i] = glm::vec4(palette(r.primitive[i]) * (0.3f + 0.7f * facing), 1.0f);
  }
}

}  // namespace

namespace {

// The primitives' triangles drawn into a framebuffer without attachments
// (the records are the output).
class PrimitiveDraw {
 public:
  PrimitiveDraw(const Scene& primitives, Extent screen, const Camera& camera) : framebuffer_(screen), camera_(camera) {
    meshes_.reserve(primitives.meshes.size());
    for (const Mesh& m : primitives.meshes) meshes_.emplace_back(m.positions, m.indices);
  }

  // The camera's view and projection into `program`.
  void set_view(const gl::ShaderProgram& program) const {
    glProgramUniformMatrix4fv(program.id(), glGetUniformLocation(program.id(), "view"), 1, GL_FALSE,
                              glm::value_ptr(camera_.view));
    glProgramUniformMatrix4fv(program.id(), glGetUniformLocation(program.id(), "projection"), 1, GL_FALSE,
                              glm::value_ptr(camera_.projection));
  }

  // Every primitive through `program`; with `ids`, each tells its index (uniform "primitive").
  void draw(const gl::ShaderProgram& program, bool ids) const {
    framebuffer_.draw_with(program, [&] {
      for (std::size_t id = 0; id < meshes_.size(); ++id) {
        if (ids) program.set("primitive", static_cast<unsigned>(id));
        meshes_[id].draw();
      }
    });
  }

 private:
  EmptyFramebuffer framebuffer_;
  Camera camera_;
  std::vector<GpuTriangles> meshes_;
};

// Every pixel's visible primitive and depth code by the expression.
void resolve_pixels(const FragmentBuffer& buffer, const CsgExpression& expression, Extent screen, CsgRender& r) {
  r.primitive.assign(screen.area(), -1);
  r.codes.assign(screen.area(), 0);
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) {
      buffer.list(x, y, list);
      std::sort(list.begin(), list.end(), [](const ListEntry& a, const ListEntry& b) { return a.code > b.code; });
      const CsgSurface surface = csg_resolve(list, expression, kCsgCoincidentCodes);
      if (!surface.visible) continue;
      const std::size_t i = x + std::size_t{y} * screen.x;
      r.primitive[i] = static_cast<std::int32_t>(surface.primitive);
      r.codes[i] = surface.code;
    }
}

}  // namespace

CsgRender render_csg(const Scene& primitives, const CsgExpression& expression, const CsgRenderSettings& s) {
  if (expression.primitives() != primitives.meshes.size())
    throw CsgError("csg: the expression names " + std::to_string(expression.primitives()) + " primitives, the scene has " +
                   std::to_string(primitives.meshes.size()) + " meshes");
  check_screen_fits(s.screen, "csg: --size");  // before any GL object of that size is made
  CsgRender r;
  r.camera = frame_scene(primitives, s.camera, s.screen);
  std::unique_ptr<FragmentBuffer> buffer;
  std::optional<RecordLayout> layout;
  const auto t0 = Clock::now();
  {
    const PrimitiveDraw draw(primitives, s.screen, r.camera);
    RecordGather g = gather_records(s.screen, s.cpu, s.threads,
                                    {kVertex, kCrossing, "csg",
                                     [&](const gl::ShaderProgram& p) {
                                       draw.set_view(p);
                                       p.set("near_plane", r.camera.near_plane);
                                       p.set("far_plane", r.camera.far_plane);
                                     },
                                     [&](const gl::ShaderProgram& p) { draw.draw(p, true); }});
    r.counters = g.counters;
    r.attempts = g.attempts;
    r.list_bytes = g.list_bytes;
    if (r.counters.failures() > 0)
      throw gl::GlError("csg: " + std::to_string(r.counters.failures()) + " of " +
                        std::to_string(r.counters.fragments) + " records lost after " + std::to_string(r.attempts) +
                        " gathers: a lost record is a wrong pixel");
    buffer = std::move(g.buffer);
    layout = g.layout;
  }
  r.gather_ms = ms_since(t0);
  const auto p0 = Clock::now();
  resolve_pixels(*buffer, expression, s.screen, r);
  shade(r, *layout, s.screen);
  r.resolve_ms = ms_since(p0);
  gl::check_gl_errors("csg");
  return r;
}

CsgCheck check_csg(const Scene& primitives, const CsgExpression& expression, const CsgRender& r, Extent screen) {
  std::vector<bool> band;
  const std::vector<std::int32_t> want = csg_reference(primitives, expression, r.camera, screen, &band);
  CsgCheck c;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (band[i]) ++c.band;
    else c.mismatches += want[i] != r.primitive[i];
  }
  return c;
}

std::vector<std::int32_t> csg_reference(const Scene& primitives, const CsgExpression& expression, const Camera& camera,
                                        Extent screen, std::vector<bool>* band) {
  const TransmittanceReference reference(primitives);
  const RecordLayout layout(Layout::L64, BufferConfig{}.age_bits);
  // The visible primitive and code along the ray through window position (wx, wy).
  const auto cast = [&](double wx, double wy) {
    const glm::dvec3 near_point = unproject(camera, screen, {wx, wy}, 0.0), far_point = unproject(camera, screen, {wx, wy}, 1.0);
    LightView to_far;  // a "spot" at the far point: hits from the near point toward it
    to_far.orthographic = false;
    to_far.position = glm::vec3(far_point);
    const double length = glm::length(far_point - near_point);
    std::vector<ListEntry> list;
    for (const TransmittanceReference::Hit& h : reference.crossings(near_point, to_far, 1e-9 * length))
      list.push_back({0, layout.depth_code(static_cast<float>(h.distance / length)), csg_data(h.mesh, h.toward)});
    std::stable_sort(list.begin(), list.end(), [](const ListEntry& a, const ListEntry& b) { return a.code > b.code; });
    const CsgSurface s = csg_resolve(list, expression, kCsgCoincidentCodes);
    bool tie = false;
    if (s.visible)
      for (const ListEntry& e : list)
        tie = tie || ((e.data >> 1) != s.primitive && std::abs(static_cast<double>(e.code) - s.code) <= 4.0);
    return std::pair{s.visible ? static_cast<std::int32_t>(s.primitive) : -1, tie};
  };
  std::vector<std::int32_t> out(screen.area(), -1);
  if (band) band->assign(screen.area(), false);
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) {
      const std::size_t i = x + std::size_t{y} * screen.x;
      const auto [id, tie] = cast(x + 0.5, y + 0.5);
      out[i] = id;
      if (!band) continue;
      bool near = tie;
      for (const auto& [dx, dy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
        near = near || cast(x + 0.5 + dx / 256.0, y + 0.5 + dy / 256.0).first != id;
      (*band)[i] = near;
    }
  return out;
}

}  // namespace habuffer
