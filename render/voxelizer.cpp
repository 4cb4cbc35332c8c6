#include "habuffer/render/voxelizer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "gpu_triangles.h"
#include "record_gather.h"
#include "habuffer/atomic_file.h"
#include "habuffer/bounded_read.h"
#include "habuffer/little_endian.h"
#include "habuffer/csv.h"
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
  // A flat mesh encloses nothing, and a grid of a flat box has cells of no
  // size that no grid file can place: refused before any work or file.
  const glm::vec3 size = b.hi - b.lo;
  if (!s.box && !(size.x > 0.0f && size.y > 0.0f && size.z > 0.0f)) {
    const char* axis = !(size.x > 0.0f) ? "x" : !(size.y > 0.0f) ? "y" : "z";
    char sides[96];
    std::snprintf(sides, sizeof sides, "%g x %g x %g", static_cast<double>(size.x), static_cast<double>(size.y),
                  static_cast<double>(size.z));
    throw SceneError("mesh '" + scene.name + "' is flat along " + axis + " (its bounding box is " + sides +
                     "): it encloses no volume to voxelize");
  }
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
GpuTriangles scene_triangles(const Scene& scene, VoxelAxis axis) {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    const auto base = static_cast<std::uint32_t>(positions.size());
    for (const glm::vec3& p : m.positions) positions.push_back(permute(p, axis));
    for (std::uint32_t i : m.indices) indices.push_back(base + i);
  }
  return GpuTriangles(positions, indices);
}

// Returns whether the column's crossings are odd (not a closed surface).
bool column_parity(std::vector<ListEntry>& crossings, const RecordLayout& layout, std::uint32_t i, std::uint32_t j,
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
  return crossings.size() % 2 == 1;
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

namespace {

// The records' statistics of a gather into `out`; throws GlError when a crossing was lost.
void gather_stats(const RecordGather& g, Voxelization& out) {
  const Counters& counters = g.counters;
  out.stats.attempts = g.attempts;
  out.stats.list_bytes = g.list_bytes;
  out.stats.counters = counters;
  out.stats.merged = counters.duplicates;
  out.stats.table_slots = g.table.area();
  out.stats.load_factor =
      static_cast<double>(counters.stored()) / static_cast<double>(std::max<std::uint64_t>(1, out.stats.table_slots));
  if (counters.failures() > 0)
    throw gl::GlError("voxelize: " + std::to_string(counters.failures()) + " of " +
                      std::to_string(counters.fragments) + " crossings lost after " +
                      std::to_string(out.stats.attempts) + " gathers (table " + g.table.str() +
                      "): a lost crossing is a wrong column; a smaller --grid needs a smaller table");
}

// The crossings of the scene's triangles along s.axis through the grid's
// columns (gather_records sizes the table from a counting pass).
RecordGather gather_crossings(const Scene& scene, const VoxelizeSettings& s, const Bounds& box) {
  const Extent screen{s.grid, s.grid};
  check_screen_fits(screen, "voxelize: --grid " + std::to_string(s.grid) + ": a view of");
  const GpuTriangles meshes = scene_triangles(scene, s.axis);
  const glm::vec3 lo = permute(box.lo, s.axis), extent = permute(box.hi - box.lo, s.axis);
  const EmptyFramebuffer framebuffer(screen);
  const auto set_box = [&](const gl::ShaderProgram& p) {
    p.set("lo", lo.x, lo.y, lo.z);
    p.set("extent", extent.x, extent.y, extent.z);
  };
  const auto draw = [&](const gl::ShaderProgram& p) { framebuffer.draw_with(p, [&] { meshes.draw(); }); };
  return gather_records(screen, s.cpu, s.threads, {kVertex, kCrossing, "voxelize", set_box, draw});
}

}  // namespace

Voxelization voxelize(const Scene& scene, const VoxelizeSettings& s) {
  s.validate();
  const Bounds box = grid_box(scene, s);
  Voxelization out;
  const auto t0 = Clock::now();
  const RecordGather g = gather_crossings(scene, s, box);
  out.stats.gather_ms = ms_since(t0);
  gather_stats(g, out);
  const auto p0 = Clock::now();
  const RecordLayout layout = g.layout;
  out.grid = VoxelGrid(s.grid, box);
  std::vector<ListEntry> crossings;
  for (std::uint32_t j = 0; j < s.grid; ++j)
    for (std::uint32_t i = 0; i < s.grid; ++i) {
      g.buffer->list(i, j, crossings);
      out.stats.odd_columns += column_parity(crossings, layout, i, j, s.axis, out.grid);
    }
  out.stats.parity_ms = ms_since(p0);
  gl::check_gl_errors("voxelize");
  return out;
}

Voxelization voxelize_voting(const Scene& scene, const VoxelizeSettings& settings) {
  Voxelization votes[3];
  for (int a = 0; a < 3; ++a) {
    VoxelizeSettings s = settings;
    s.axis = static_cast<VoxelAxis>(a);
    votes[a] = voxelize(scene, s);
  }
  Voxelization out;
  out.grid = VoxelGrid(settings.grid, votes[0].grid.box);
  for (std::size_t w = 0; w < out.grid.words.size(); ++w) {
    const std::uint64_t x = votes[0].grid.words[w], y = votes[1].grid.words[w], z = votes[2].grid.words[w];
    out.grid.words[w] = (x & y) | (y & z) | (x & z);  // two of three
  }
  for (const Voxelization& v : votes) {
    out.stats.counters += v.stats.counters;
    out.stats.merged += v.stats.merged;
    out.stats.attempts += v.stats.attempts;
    out.stats.table_slots = std::max(out.stats.table_slots, v.stats.table_slots);
    out.stats.list_bytes = std::max(out.stats.list_bytes, v.stats.list_bytes);
    out.stats.gather_ms += v.stats.gather_ms;
    out.stats.parity_ms += v.stats.parity_ms;
    out.stats.odd_columns += v.stats.odd_columns;
  }
  out.stats.load_factor = votes[2].stats.load_factor;
  return out;
}

namespace {

constexpr char kGridMagic[8] = {'H', 'A', 'V', 'O', 'X', 'E', 'L', '1'};
constexpr std::size_t kGridHeader = 40;


}  // namespace

void save_voxel_grid(const std::string& path, const VoxelGrid& grid) {
  std::string bytes(kGridMagic, sizeof kGridMagic);
  put_le<std::uint32_t>(bytes, grid.n);
  put_le<std::uint32_t>(bytes, 0);
  for (const float f : {grid.box.lo.x, grid.box.lo.y, grid.box.lo.z, grid.box.hi.x, grid.box.hi.y, grid.box.hi.z})
    put_le<float>(bytes, f);
  for (const std::uint64_t w : grid.words) put_le<std::uint64_t>(bytes, w);
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

void save_voxel_nrrd(const std::string& path, const VoxelGrid& grid, const std::string& comment) {
  std::string note = comment;
  std::replace(note.begin(), note.end(), '\n', ' ');
  std::replace(note.begin(), note.end(), '\r', ' ');
  const glm::dvec3 lo(grid.box.lo), size = (glm::dvec3(grid.box.hi) - lo) / static_cast<double>(grid.n);
  const glm::dvec3 origin = lo + 0.5 * size;
  char geometry[512];
  std::snprintf(geometry, sizeof geometry,
                "space dimension: 3\nspace directions: (%.9g,0,0) (0,%.9g,0) (0,0,%.9g)\n"
                "space origin: (%.9g,%.9g,%.9g)\n",
                size.x, size.y, size.z, origin.x, origin.y, origin.z);
  std::string header = "NRRD0004\n";
  if (!note.empty()) header += "# " + note + "\n";
  header += "# habuffer solid voxels: 1 solid, 0 empty; x fastest\ntype: uint8\ndimension: 3\n";
  const std::string n = std::to_string(grid.n);
  header += "sizes: " + n + " " + n + " " + n + "\n";
  header += geometry;
  header += "kinds: domain domain domain\ncenters: cell cell cell\nencoding: raw\n\n";
  AtomicFile file(path);
  file.write(header);
  std::string row(grid.n, '\0');
  for (std::uint32_t z = 0; z < grid.n; ++z)
    for (std::uint32_t y = 0; y < grid.n; ++y) {
      for (std::uint32_t x = 0; x < grid.n; ++x) row[x] = grid.solid(x, y, z) ? '\1' : '\0';
      file.write(row);
    }
  file.commit();
}

VoxelGrid load_voxel_grid(const std::string& path) {
  // The largest grid file: side 4096, 4096^3 bits.
  constexpr std::uint64_t kMaxGridBytes = kGridHeader + (std::uint64_t{4096} * 4096 * 4096 / 64) * 8;
  return parse_voxel_grid(read_file_bounded(path, "voxel grid", kMaxGridBytes), path);
}

VoxelGrid parse_voxel_grid(const std::string& bytes, const std::string& path) {
  if (bytes.size() < kGridHeader || bytes.compare(0, 8, kGridMagic, 8) != 0)
    throw DataError(path + ": not a voxel grid (no HAVOXEL1 header)");
  const auto n = take_le<std::uint32_t>(bytes, 8);
  if (n == 0 || n > 4096) throw DataError(path + ": voxel grid side " + std::to_string(n) + " is outside 1..4096");
  const std::uint64_t words = (std::uint64_t{n} * n * n + 63) / 64;
  if (bytes.size() != kGridHeader + words * 8)
    throw DataError(path + ": " + std::to_string(bytes.size()) + " bytes, a grid of side " + std::to_string(n) +
                    " has " + std::to_string(kGridHeader + words * 8));
  Bounds box;
  box.add({take_le<float>(bytes, 16), take_le<float>(bytes, 20), take_le<float>(bytes, 24)});
  box.add({take_le<float>(bytes, 28), take_le<float>(bytes, 32), take_le<float>(bytes, 36)});
  if (!(box.hi.x > box.lo.x && box.hi.y > box.lo.y && box.hi.z > box.lo.z))
    throw DataError(path + ": the voxel grid's box is empty or not finite");
  VoxelGrid g(n, box);
  for (std::uint64_t w = 0; w < words; ++w) g.words[w] = take_le<std::uint64_t>(bytes, kGridHeader + w * 8);
  // The last word's bits past voxel n^3 - 1 are padding: set, they would be
  // voxels outside the grid (found by fuzz_voxel_file).
  if (const std::uint64_t used = (std::uint64_t{n} * n * n) % 64; used != 0 && (g.words.back() >> used) != 0)
    throw DataError(path + ": the voxel grid sets padding bits past its " + std::to_string(std::uint64_t{n} * n * n) +
                    " voxels (side " + std::to_string(n) + ")");
  return g;
}

VoxelCheck check_voxels(const Scene& scene, const VoxelizeSettings& s, const VoxelGrid& got) {
  std::vector<bool> band;
  const VoxelGrid want = voxel_reference(scene, s, &band);
  VoxelCheck c;
  for (std::uint32_t z = 0; z < got.n; ++z)
    for (std::uint32_t y = 0; y < got.n; ++y)
      for (std::uint32_t x = 0; x < got.n; ++x) {
        if (band[x + std::uint64_t{got.n} * (y + std::uint64_t{got.n} * z)]) ++c.band;
        else c.mismatches += got.solid(x, y, z) != want.solid(x, y, z);
      }
  return c;
}

VoxelCheck check_voxels_voting(const Scene& scene, const VoxelizeSettings& settings, const VoxelGrid& got) {
  std::vector<bool> bands[3];
  VoxelGrid want[3];
  for (int a = 0; a < 3; ++a) {
    VoxelizeSettings s = settings;
    s.axis = static_cast<VoxelAxis>(a);
    want[a] = voxel_reference(scene, s, &bands[a]);
  }
  VoxelCheck c;
  for (std::uint32_t z = 0; z < got.n; ++z)
    for (std::uint32_t y = 0; y < got.n; ++y)
      for (std::uint32_t x = 0; x < got.n; ++x) {
        const std::uint64_t i = x + std::uint64_t{got.n} * (y + std::uint64_t{got.n} * z);
        if (bands[0][i] || bands[1][i] || bands[2][i]) {
          ++c.band;
          continue;
        }
        const int votes = int{want[0].solid(x, y, z)} + int{want[1].solid(x, y, z)} + int{want[2].solid(x, y, z)};
        c.mismatches += got.solid(x, y, z) != (votes >= 2);
      }
  return c;
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
  const double same = 1e-9 * glm::length(extent);  // one crossing of a surface (TransmittanceReference::crossings)
  const auto crossings_w = [&](double u, double v) {
    std::vector<double> w;
    for (const TransmittanceReference::Hit& h : reference.crossings(unpermute({u, v, far_w}, s.axis), along, same))
      w.push_back(far_w - h.distance);
    std::sort(w.begin(), w.end());
    return w;
  };
  const double du = extent.x / n, dv = extent.y / n, dw = extent.z / n;
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const double u = lo.x + (i + 0.5) * du, v = lo.y + (j + 0.5) * dv;
      // The column's ray, and four rays 1/512 voxel beside it (the snapping's
      // largest move of a coordinate): where their
      // parities differ, an edge passes within the rasterizer's snapping.
      std::vector<double> rays[5] = {crossings_w(u, v)};
      if (band) {
        int r = 1;
        for (const auto& [ou, ov] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
          rays[r++] = crossings_w(u + ou * du / 512.0, v + ov * dv / 512.0);
      }
      std::size_t before[5] = {0, 0, 0, 0, 0};
      for (std::uint32_t k = 0; k < n; ++k) {
        const double centre = lo.z + (k + 0.5) * dw;
        for (int r = 0; r < (band ? 5 : 1); ++r)
          while (before[r] < rays[r].size() && rays[r][before[r]] < centre) ++before[r];
        const glm::uvec3 vox = voxel_of(i, j, k, s.axis);
        if (before[0] % 2 == 1) grid.set(vox.x, vox.y, vox.z);
        if (band) {
          bool near = false;
          for (int r = 1; r < 5; ++r) near = near || before[r] % 2 != before[0] % 2;
          for (const double c : rays[0]) near = near || std::abs(c - centre) <= band_depth * dw;
          (*band)[vox.x + std::uint64_t{n} * (vox.y + std::uint64_t{n} * vox.z)] = near;
        }
      }
    }
  return grid;
}

}  // namespace habuffer
