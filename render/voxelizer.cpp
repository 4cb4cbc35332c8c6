#include "habuffer/render/voxelizer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "habuffer/fragment_streams.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/light_view.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

constexpr std::uint32_t kFront = 1, kBack = 2;  // the facing in a record's data word

// The view's coordinates: the axis last (cyclic, so triangles keep their winding).
glm::vec3 permute(glm::vec3 p, VoxelAxis a) {
  switch (a) {
    case VoxelAxis::X: return {p.y, p.z, p.x};
    case VoxelAxis::Y: return {p.z, p.x, p.y};
    case VoxelAxis::Z: break;
  }
  return p;
}
glm::dvec3 unpermute(glm::dvec3 q, VoxelAxis a) {
  switch (a) {
    case VoxelAxis::X: return {q.z, q.x, q.y};
    case VoxelAxis::Y: return {q.y, q.z, q.x};
    case VoxelAxis::Z: break;
  }
  return q;
}
glm::uvec3 voxel_of(std::uint32_t i, std::uint32_t j, std::uint32_t k, VoxelAxis a) {
  const glm::dvec3 v = unpermute(glm::dvec3(i, j, k), a);
  return {static_cast<std::uint32_t>(v.x), static_cast<std::uint32_t>(v.y), static_cast<std::uint32_t>(v.z)};
}

Bounds grid_box(const Scene& scene, const VoxelizeSettings& s) {
  const Bounds b = scene.bounds();
  if (b.empty()) throw SceneError("scene '" + scene.name + "' has no vertices to voxelize");
  if (!s.box) return b;
  if (glm::any(glm::lessThan(b.lo, s.box->lo)) || glm::any(glm::greaterThan(b.hi, s.box->hi)))
    throw std::invalid_argument("voxelize: the grid's box must hold the whole scene (crossings outside it decide "
                                "the parity inside)");
  return *s.box;
}

const char* const kVertex = R"(#version 450 core
layout(location = 0) in vec3 position;  // the axis last
uniform vec3 lo;
uniform vec3 extent;
out float v_t;
void main() {
  vec3 q = (position - lo) / extent;  // the box as [0, 1]^3
  v_t = q.z;
  gl_Position = vec4(q.xy * 2.0 - 1.0, q.z * 2.0 - 1.0, 1.0);
}
)";
const char* const kCrossing = R"(
in float v_t;
void main() { habuffer_insert(uvec2(gl_FragCoord.xy), clamp(v_t, 0.0, 1.0), gl_FrontFacing ? 1u : 2u); }
)";

// Every triangle of the scene in one buffer, permuted for the axis.
struct GpuMeshes {
  GpuMeshes(const Scene& scene, VoxelAxis axis) {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (const Mesh& m : scene.meshes) {
      const auto base = static_cast<std::uint32_t>(positions.size());
      for (const glm::vec3& p : m.positions) positions.push_back(permute(p, axis));
      for (std::uint32_t i : m.indices) indices.push_back(base + i);
    }
    count = static_cast<GLsizei>(indices.size());
    vertices = gl::GlStorage(positions.size() * sizeof(glm::vec3), positions.data());
    elements = gl::GlStorage(indices.size() * 4, indices.data());
    glCreateVertexArrays(1, &array);
    glVertexArrayVertexBuffer(array, 0, vertices.id(), 0, sizeof(glm::vec3));
    glVertexArrayElementBuffer(array, elements.id());
    glEnableVertexArrayAttrib(array, 0);
    glVertexArrayAttribFormat(array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(array, 0, 0);
  }
  ~GpuMeshes() { glDeleteVertexArrays(1, &array); }
  GpuMeshes(const GpuMeshes&) = delete;
  GpuMeshes& operator=(const GpuMeshes&) = delete;
  gl::GlStorage vertices, elements;
  GLuint array = 0;
  GLsizei count = 0;
};

// The lists' parity at each voxel centre of column (i, j).
void column_parity(std::vector<ListEntry>& crossings, const RecordLayout& layout, std::uint32_t i, std::uint32_t j,
                   VoxelAxis axis, VoxelGrid& grid) {
  std::sort(crossings.begin(), crossings.end(), [](const ListEntry& a, const ListEntry& b) { return a.code > b.code; });
  std::size_t nearer = 0;  // crossings with a code above the centre's: nearer than it
  for (std::uint32_t k = 0; k < grid.n; ++k) {
    const std::uint32_t centre =
        layout.depth_code((static_cast<float>(k) + 0.5f) / static_cast<float>(grid.n));
    while (nearer < crossings.size() && crossings[nearer].code > centre) ++nearer;
    if (nearer % 2 == 1) {
      const glm::uvec3 v = voxel_of(i, j, k, axis);
      grid.set(v.x, v.y, v.z);
    }
  }
}

}  // namespace

std::string to_string(VoxelAxis a) { return a == VoxelAxis::X ? "x" : a == VoxelAxis::Y ? "y" : "z"; }

VoxelGrid::VoxelGrid(std::uint32_t side, Bounds region) : n(side), box(region) {
  if (side == 0 || side > 4096) throw std::invalid_argument("voxel grid: " + std::to_string(side) + " voxels per side is outside 1..4096");
  const std::uint64_t voxels = std::uint64_t{side} * side * side;
  words.assign((voxels + 63) / 64, 0);
}

bool VoxelGrid::solid(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
  const std::uint64_t i = x + std::uint64_t{n} * (y + std::uint64_t{n} * z);
  return (words[i / 64] >> (i % 64)) & 1u;
}

void VoxelGrid::set(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool on) {
  const std::uint64_t i = x + std::uint64_t{n} * (y + std::uint64_t{n} * z);
  const std::uint64_t bit = std::uint64_t{1} << (i % 64);
  words[i / 64] = on ? words[i / 64] | bit : words[i / 64] & ~bit;
}

std::uint64_t VoxelGrid::count() const {
  std::uint64_t c = 0;
  for (const std::uint64_t w : words) c += static_cast<std::uint64_t>(std::popcount(w));
  return c;
}

void VoxelizeSettings::validate() const {
  if (grid == 0 || grid > 4096) throw std::invalid_argument("--grid " + std::to_string(grid) + " is outside 1..4096");
  if (box && !(box->hi.x > box->lo.x && box->hi.y > box->lo.y && box->hi.z > box->lo.z))
    throw std::invalid_argument("voxelize: the grid's box has a side that is not positive");
}

Voxelization voxelize(const Scene& scene, const VoxelizeSettings& s) {
  s.validate();
  const Bounds box = grid_box(scene, s);
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode) throw gl::GlError("voxelize: L64 records need 64-bit shader types (GL_ARB_gpu_shader_int64), which this OpenGL lacks");
  const Extent screen{s.grid, s.grid};
  BufferConfig config;
  config.screen = screen;
  config.layout = Layout::L64;
  // A closed surface crosses a column an even number of times: start from two per pixel.
  config.table = table_for_load(screen, 2 * screen.area(), 0.5);
  gl::GlFrameOptions options;
  options.max_attempts = 16;  // lossless: a gather that drops a crossing is redone larger
  gl::GlHaBuffer lists(config, OffsetSource{}, *mode, options);
  const gl::ShaderProgram program = gl::ShaderProgram::graphics(
      kVertex, lists.module_source(gl::ShaderStage::Fragment) + kCrossing, "voxelization gather");
  const GpuMeshes meshes(scene, s.axis);
  const glm::vec3 lo = permute(box.lo, s.axis), extent = permute(box.hi - box.lo, s.axis);
  program.set("lo", lo.x, lo.y, lo.z);
  program.set("extent", extent.x, extent.y, extent.z);
  GLuint framebuffer = 0;  // no attachment: the gather writes no colour
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(s.grid));
  glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(s.grid));
  Voxelization out;
  const auto t0 = Clock::now();
  const gl::FrameReport report = lists.frame([&] {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, static_cast<GLsizei>(s.grid), static_cast<GLsizei>(s.grid));
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // both facings: entries and exits
    glDisable(GL_BLEND);
    glUseProgram(program.id());
    glBindVertexArray(meshes.array);
    glDrawElements(GL_TRIANGLES, meshes.count, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  });
  glDeleteFramebuffers(1, &framebuffer);
  out.stats.gather_ms = ms_since(t0);
  out.stats.counters = report.counters;
  out.stats.merged = report.counters.duplicates;
  out.stats.attempts = static_cast<std::uint32_t>(report.attempts.size());
  out.stats.table_slots = lists.table().area();
  out.stats.load_factor =
      static_cast<double>(report.counters.stored()) / static_cast<double>(std::max<std::uint64_t>(1, out.stats.table_slots));
  out.stats.list_bytes = lists.technique().memory_bytes();
  if (report.counters.failures() > 0)
    throw gl::GlError("voxelize: " + std::to_string(report.counters.failures()) + " of " +
                      std::to_string(report.counters.fragments) + " crossings lost after " +
                      std::to_string(out.stats.attempts) + " gathers (table " + lists.table().str() +
                      "): a lost crossing is a wrong column; a smaller --grid needs a smaller table");
  const auto p0 = Clock::now();
  const std::unique_ptr<FragmentBuffer> buffer = lists.technique().read_back();
  const RecordLayout layout = config.record_layout();
  out.grid = VoxelGrid(s.grid, box);
  std::vector<ListEntry> crossings;
  for (std::uint32_t j = 0; j < s.grid; ++j)
    for (std::uint32_t i = 0; i < s.grid; ++i) {
      buffer->list(i, j, crossings);
      column_parity(crossings, layout, i, j, s.axis, out.grid);
    }
  out.stats.parity_ms = ms_since(p0);
  gl::check_gl_errors("voxelize");
  return out;
}

VoxelGrid voxel_reference(const Scene& scene, const VoxelizeSettings& s, std::vector<bool>* band, double band_depth) {
  s.validate();
  const Bounds box = grid_box(scene, s);
  const TransmittanceReference reference(scene);
  const glm::dvec3 lo = glm::dvec3(permute(box.lo, s.axis)), extent = glm::dvec3(permute(box.hi - box.lo, s.axis));
  LightView along;  // an orthographic "light" whose rays run along the axis toward its low end
  along.orthographic = true;
  along.direction = glm::vec3(unpermute(glm::dvec3(0.0, 0.0, 1.0), s.axis));
  const double far_w = lo.z + 2.0 * extent.z;  // every column's ray starts beyond the box
  VoxelGrid grid(s.grid, box);
  const std::uint32_t n = s.grid;
  if (band) band->assign(std::uint64_t{n} * n * n, false);
  const auto crossings_w = [&](double u, double v) {
    std::vector<double> w;
    for (const TransmittanceReference::Hit& h : reference.hits(unpermute({u, v, far_w}, s.axis), along))
      w.push_back(far_w - h.distance);
    std::sort(w.begin(), w.end());
    return w;
  };
  const double du = extent.x / n, dv = extent.y / n, dw = extent.z / n;
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const double u = lo.x + (i + 0.5) * du, v = lo.y + (j + 0.5) * dv;
      const std::vector<double> w = crossings_w(u, v);
      bool edge = false;
      for (const auto& [ou, ov] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
        edge = edge || crossings_w(u + ou * du / 128.0, v + ov * dv / 128.0).size() != w.size();
      std::size_t before = 0;
      for (std::uint32_t k = 0; k < n; ++k) {
        const double centre = lo.z + (k + 0.5) * dw;
        while (before < w.size() && w[before] < centre) ++before;
        const glm::uvec3 vox = voxel_of(i, j, k, s.axis);
        if (before % 2 == 1) grid.set(vox.x, vox.y, vox.z);
        if (band) {
          bool near = edge;
          for (const double c : w) near = near || std::abs(c - centre) <= band_depth * dw;
          (*band)[vox.x + std::uint64_t{n} * (vox.y + std::uint64_t{n} * vox.z)] = near;
        }
      }
    }
  return grid;
}

}  // namespace habuffer
