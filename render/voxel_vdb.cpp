// Voxel grids as OpenVDB files (see habuffer/render/voxel_vdb.h).
#include "habuffer/render/voxel_vdb.h"

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <ios>
#include <mutex>
#include <sstream>
#include <type_traits>

#include "habuffer/atomic_file.h"
#include "habuffer/data_error.h"
#include "habuffer/fenced_call.h"
#include "habuffer/little_endian.h"
#include "habuffer/memory_budget.h"
#include "habuffer/printable.h"

namespace habuffer {
namespace {

constexpr const char* kGridName = "solid";
constexpr std::int64_t kMaxSide = 4096;  // VoxelGrid's largest side

void initialize() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string box_text(const openvdb::CoordBBox& b) {
  const auto c = [](const openvdb::Coord& p) {
    return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + ")";
  };
  return c(b.min()) + ".." + c(b.max());
}

openvdb::Vec3s vec(glm::vec3 v) { return {v.x, v.y, v.z}; }
glm::vec3 vec(const openvdb::Vec3s& v) { return {v.x(), v.y(), v.z()}; }

// Index (x, y, z) at the centre of its cell of `grid.box`.
openvdb::math::Transform::Ptr cell_transform(const VoxelGrid& grid) {
  const openvdb::Vec3d lo(grid.box.lo.x, grid.box.lo.y, grid.box.lo.z), hi(grid.box.hi.x, grid.box.hi.y, grid.box.hi.z);
  const openvdb::Vec3d cell = (hi - lo) / static_cast<double>(grid.n);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(1.0);
  xf->preScale(cell);
  xf->postTranslate(lo + 0.5 * cell);
  return xf;
}

// The grid's active voxels span at most kMaxSide along every axis.
void check_extent(const openvdb::CoordBBox& box, const std::string& what) {
  if (box.empty()) return;
  std::int64_t side = 0;
  for (int a = 0; a < 3; ++a)
    side = std::max<std::int64_t>(side, static_cast<std::int64_t>(box.max()[a]) - box.min()[a] + 1);
  if (side > kMaxSide)
    throw DataError(what + " spans " + std::to_string(side) + " voxels along an axis (its active voxels lie in " +
                    box_text(box) + "); at most " + std::to_string(kMaxSide));
}

// The grid read: the first named "solid", or the only one.
openvdb::GridBase::Ptr pick_grid(const openvdb::GridPtrVec& all, const std::string& path) {
  if (all.empty()) throw DataError(path + ": the OpenVDB file holds no grid");
  openvdb::GridBase::Ptr grid;
  for (const openvdb::GridBase::Ptr& g : all)
    if (!grid && g && g->getName() == kGridName) grid = g;
  if (!grid) {
    if (all.size() != 1) {
      std::string names;
      for (const openvdb::GridBase::Ptr& g : all) names += (names.empty() ? "" : ", ") + excerpt(g ? g->getName() : "");
      throw DataError(path + ": " + std::to_string(all.size()) + " grids (" + names + ") and none named 'solid'");
    }
    grid = all.front();
  }
  if (!grid) throw DataError(path + ": the OpenVDB file's grid could not be read");
  const std::string what = printable(path) + ": grid " + excerpt(grid->getName());
  if (!grid->isType<openvdb::BoolGrid>() && !grid->isType<openvdb::FloatGrid>())
    throw DataError(what + " holds " + excerpt(grid->valueType()) + " values; voxel grids are bool grids or float fog volumes");
  if (grid->getGridClass() == openvdb::GRID_LEVEL_SET)
    throw DataError(what + " is a level set (its inside is not stored as active voxels): convert it to a fog volume");
  return grid;
}

// A grid's active voxels and tiles, walked serially (the child runs no
// thread pool of the parent's; see habuffer/fenced_call.h): their bounding
// box, then the solid ones relative to `origin` as blocks and boxes.
template <class GridT>
struct Walk {
  const GridT& grid;

  static bool solid(const typename GridT::ValueType& v) {
    if constexpr (std::is_same_v<typename GridT::ValueType, bool>) return v;
    else return v > 0.0f;
  }

  openvdb::CoordBBox active_box() const {
    openvdb::CoordBBox box;
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
      if (it.isVoxelValue()) box.expand(it.getCoord());
      else box.expand(it.getBoundingBox());
    }
    return box;
  }

  void solid_voxels(const openvdb::Coord& origin, std::uint32_t n, SparseVoxels& out, const std::string& what) const {
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
      SparseVoxels::Block b;
      const openvdb::Coord o = leaf->origin() - origin;
      b.origin = {o.x(), o.y(), o.z()};
      bool any = false;
      for (auto v = leaf->cbeginValueOn(); v; ++v) {
        if (!solid(*v)) continue;
        const openvdb::Coord c = v.getCoord() - leaf->origin();
        const unsigned i = static_cast<unsigned>(c.x() + 8 * (c.y() + 8 * c.z()));
        if (i >= 512) throw DataError(what + ": a leaf holds a voxel outside its 8^3 block");
        b.bits[i / 64] |= std::uint64_t{1} << (i % 64);
        any = true;
      }
      if (any) out.blocks.push_back(b);
    }
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
      if (it.isVoxelValue() || !solid(*it)) continue;
      const openvdb::CoordBBox t = it.getBoundingBox();
      SparseVoxels::Box b;
      for (int a = 0; a < 3; ++a) {
        const std::int64_t lo = static_cast<std::int64_t>(t.min()[a]) - origin[a], hi = static_cast<std::int64_t>(t.max()[a]) - origin[a];
        if (lo < 0 || hi >= n) throw DataError(what + ": a tile lies outside the grid of side " + std::to_string(n));
        b.lo[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(lo);
        b.hi[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(hi);
      }
      out.boxes.push_back(b);
    }
  }
};

// Side, box and index origin: habuffer's metadata, else the active voxels'
// bounding cube placed by the transform.
void place(const openvdb::GridBase& g, const openvdb::CoordBBox& active, const std::string& path, SparseVoxels& out,
           openvdb::Coord& origin) {
  const std::string what = printable(path) + ": grid " + excerpt(g.getName());
  if (g["habuffer_side"]) {
    const std::int32_t side = g.metaValue<openvdb::Int32>("habuffer_side");
    if (side < 1 || side > kMaxSide)
      throw DataError(path + ": habuffer_side " + std::to_string(side) + " is outside 1.." + std::to_string(kMaxSide));
    out.n = static_cast<std::uint32_t>(side);
    out.box.add(vec(g.metaValue<openvdb::Vec3s>("habuffer_box_lo")));
    out.box.add(vec(g.metaValue<openvdb::Vec3s>("habuffer_box_hi")));
    const openvdb::Coord a = active.min(), b = active.max();
    if (!active.empty() && (std::min({a.x(), a.y(), a.z()}) < 0 || std::max({b.x(), b.y(), b.z()}) >= side))
      throw DataError(path + ": active voxels lie outside the grid of side " + std::to_string(side) + " its metadata give");
    origin = openvdb::Coord(0, 0, 0);
    return;
  }
  const openvdb::math::Transform& xf = g.transform();
  const openvdb::math::MapBase& map = *xf.baseMap();
  const bool scale_and_translation =
      map.isType<openvdb::math::ScaleTranslateMap>() || map.isType<openvdb::math::UniformScaleTranslateMap>() ||
      map.isType<openvdb::math::ScaleMap>() || map.isType<openvdb::math::UniformScaleMap>() ||
      map.isType<openvdb::math::TranslationMap>();
  if (!xf.isLinear() || !scale_and_translation)
    throw DataError(what + " has a " + excerpt(xf.baseMap()->type()) + " transform; voxel grids take a scale and a translation only");
  if (active.empty()) throw DataError(what + " has no active voxels to place a grid around");
  const openvdb::Coord extent = active.dim();
  const int side = std::max({extent.x(), extent.y(), extent.z()});
  out.n = static_cast<std::uint32_t>(side);
  origin = active.min();
  const openvdb::Vec3d lo = xf.indexToWorld(openvdb::Vec3d(origin.asVec3d()) - openvdb::Vec3d(0.5));
  const openvdb::Vec3d hi = xf.indexToWorld(openvdb::Vec3d(origin.asVec3d()) + openvdb::Vec3d(out.n - 0.5));
  out.box.add({static_cast<float>(lo.x()), static_cast<float>(lo.y()), static_cast<float>(lo.z())});
  out.box.add({static_cast<float>(hi.x()), static_cast<float>(hi.y()), static_cast<float>(hi.z())});
}

// The child's answer: n, the box, the blocks and the boxes, little-endian.
std::string encode(const SparseVoxels& v) {
  std::string out;
  put_le<std::uint32_t>(out, v.n);
  for (const float f : {v.box.lo.x, v.box.lo.y, v.box.lo.z, v.box.hi.x, v.box.hi.y, v.box.hi.z}) put_le<float>(out, f);
  put_le<std::uint64_t>(out, v.blocks.size());
  put_le<std::uint64_t>(out, v.boxes.size());
  for (const SparseVoxels::Block& b : v.blocks) {
    for (const std::int32_t o : b.origin) put_le<std::int32_t>(out, o);
    for (const std::uint64_t w : b.bits) put_le<std::uint64_t>(out, w);
  }
  for (const SparseVoxels::Box& b : v.boxes) {
    for (const std::uint32_t c : b.lo) put_le<std::uint32_t>(out, c);
    for (const std::uint32_t c : b.hi) put_le<std::uint32_t>(out, c);
  }
  return out;
}

constexpr std::size_t kHeaderBytes = 4 + 24 + 16, kBlockBytes = 12 + 64, kBoxBytes = 24;

SparseVoxels decode(const std::string& in, const std::string& path) {
  const auto broken = [&] { return DataError(path + ": the fenced OpenVDB reader's answer is malformed"); };
  if (in.size() < kHeaderBytes) throw broken();
  SparseVoxels v;
  v.n = take_le<std::uint32_t>(in, 0);
  v.box.add({take_le<float>(in, 4), take_le<float>(in, 8), take_le<float>(in, 12)});
  v.box.add({take_le<float>(in, 16), take_le<float>(in, 20), take_le<float>(in, 24)});
  const auto blocks = take_le<std::uint64_t>(in, 28), boxes = take_le<std::uint64_t>(in, 36);
  if (blocks > in.size() / kBlockBytes || boxes > in.size() / kBoxBytes ||
      in.size() != kHeaderBytes + blocks * kBlockBytes + boxes * kBoxBytes)
    throw broken();
  std::size_t at = kHeaderBytes;
  v.blocks.resize(blocks);
  for (SparseVoxels::Block& b : v.blocks) {
    for (std::int32_t& o : b.origin) o = take_le<std::int32_t>(in, (at += 4) - 4);
    for (std::uint64_t& w : b.bits) w = take_le<std::uint64_t>(in, (at += 8) - 8);
  }
  v.boxes.resize(boxes);
  for (SparseVoxels::Box& b : v.boxes) {
    for (std::uint32_t& c : b.lo) c = take_le<std::uint32_t>(in, (at += 4) - 4);
    for (std::uint32_t& c : b.hi) c = take_le<std::uint32_t>(in, (at += 4) - 4);
  }
  return v;
}

// In the child: the file's bytes parsed by OpenVDB, the grid picked, placed
// and walked into sparse voxels.
std::string parse_in_child(const std::string& bytes, const std::string& path) {
  initialize();
  openvdb::GridPtrVecPtr grids;
  try {
    std::istringstream in(bytes);
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    grids = stream.getGrids();
  } catch (const openvdb::Exception& e) {
    throw DataError(printable(path) + ": not a readable OpenVDB file: " + printable(e.what(), 160));
  } catch (const std::ios_base::failure& e) {
    throw DataError(path + ": not a readable OpenVDB file: it ends early or is corrupt");
  }
  if (!grids) throw DataError(path + ": the OpenVDB file holds no grid");
  const openvdb::GridBase::Ptr g = pick_grid(*grids, path);
  const std::string what = printable(path) + ": grid " + excerpt(g->getName());
  SparseVoxels out;
  openvdb::Coord origin;
  const auto walk = [&](const auto& typed) {
    const Walk<std::decay_t<decltype(typed)>> w{typed};
    const openvdb::CoordBBox active = w.active_box();
    check_extent(active, what);
    place(*g, active, path, out, origin);
    if (!(out.box.hi.x > out.box.lo.x && out.box.hi.y > out.box.lo.y && out.box.hi.z > out.box.lo.z))
      throw DataError(path + ": the voxel grid's box is empty or not finite");
    w.solid_voxels(origin, out.n, out, what);
  };
  if (g->isType<openvdb::BoolGrid>()) walk(static_cast<const openvdb::BoolGrid&>(*g));
  else walk(static_cast<const openvdb::FloatGrid&>(*g));
  return encode(out);
}

}  // namespace

bool has_vdb_support() { return true; }
std::string vdb_support() { return std::string("OpenVDB ") + openvdb::getLibraryVersionString(); }

void save_voxel_vdb(const std::string& path, const VoxelGrid& grid, const std::string& comment) {
  initialize();
  openvdb::BoolGrid::Ptr g = openvdb::BoolGrid::create(false);
  g->setName(kGridName);
  g->setTransform(cell_transform(grid));
  g->insertMeta("habuffer_side", openvdb::Int32Metadata(static_cast<std::int32_t>(grid.n)));
  g->insertMeta("habuffer_box_lo", openvdb::Vec3SMetadata(vec(grid.box.lo)));
  g->insertMeta("habuffer_box_hi", openvdb::Vec3SMetadata(vec(grid.box.hi)));
  if (!comment.empty()) g->insertMeta("habuffer_comment", openvdb::StringMetadata(comment));
  openvdb::BoolGrid::Accessor acc = g->getAccessor();
  for (std::uint32_t z = 0; z < grid.n; ++z)
    for (std::uint32_t y = 0; y < grid.n; ++y)
      for (std::uint32_t x = 0; x < grid.n; ++x)
        if (grid.solid(x, y, z)) acc.setValueOn(openvdb::Coord(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)), true);
  g->pruneGrid();  // uniform blocks become tiles
  AtomicFile out(path, AtomicFile::Access::ByName);
  try {
    openvdb::io::File file(out.staging_path());
    file.write({g});
    file.close();
  } catch (const openvdb::Exception& e) {
    throw DataError(path + ": OpenVDB could not write it: " + e.what());
  }
  out.commit();
}

SparseVoxels parse_vdb_bytes(const std::string& bytes, const std::string& path) {
  // What a file of this size may ask: OpenVDB holds the bytes parsed as a
  // tree of about their size (bool leaves are bitmasks; compressed leaves
  // expand), 64 times over plus 256 MiB, and a second of CPU time per MiB
  // beyond the first 30 s. A corrupt length asking for gigabytes, or a loop,
  // is stopped there.
  FenceLimits limits;
  limits.memory_bytes = (std::uint64_t{256} << 20) + saturating_product(bytes.size(), 64);
  if (const std::uint64_t machine = physical_memory_bytes(); machine > 0) limits.memory_bytes = std::min(limits.memory_bytes, machine);
  limits.cpu_seconds = 30 + static_cast<std::uint32_t>(std::min<std::uint64_t>(bytes.size() >> 20, 3600));
  return decode(fenced_call(path + ": OpenVDB's reader", [&] { return parse_in_child(bytes, path); }, limits), path);
}

}  // namespace habuffer
