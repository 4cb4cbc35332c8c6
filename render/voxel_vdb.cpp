// Voxel grids as OpenVDB files (see habuffer/render/voxel_vdb.h).
#include "habuffer/render/voxel_vdb.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "habuffer/atomic_file.h"
#include "habuffer/data_error.h"
#include "habuffer/memory_budget.h"

namespace habuffer {
namespace {

constexpr const char* kGridName = "solid";
constexpr std::int64_t kMaxSide = 4096;  // VoxelGrid's largest side

void initialize() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
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

// The grid's active voxels span at most kMaxSide along every axis, and its
// grid of side n (the largest span) fits in memory as n^3 bits: checked from
// the file's bounding-box metadata before any voxel is read where the
// writer stored it (OpenVDB does by default), and from the grid read otherwise.
void check_extent(const openvdb::Coord& lo, const openvdb::Coord& hi, const std::string& what) {
  std::int64_t side = 0;
  for (int a = 0; a < 3; ++a) side = std::max<std::int64_t>(side, static_cast<std::int64_t>(hi[a]) - lo[a] + 1);
  if (side > kMaxSide)
    throw DataError(what + " spans " + std::to_string(side) + " voxels along an axis; at most " + std::to_string(kMaxSide));
  const auto n = static_cast<std::uint64_t>(std::max<std::int64_t>(side, 1));
  try {
    check_fits_in_memory(what + " (a grid of side " + std::to_string(n) + ")", n * n * n / 8 + 8);
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }
}

// The grid `load_voxel_vdb` reads: the first named "solid", or the only one.
openvdb::GridBase::Ptr pick_grid(openvdb::io::File& file, const std::string& path) {
  const openvdb::GridPtrVecPtr all = file.readAllGridMetadata();
  if (all->empty()) throw DataError(path + ": the OpenVDB file holds no grid");
  openvdb::GridBase::Ptr meta;
  for (const openvdb::GridBase::Ptr& g : *all)
    if (!meta && g->getName() == kGridName) meta = g;
  if (!meta) {
    if (all->size() != 1) {
      std::string names;
      for (const openvdb::GridBase::Ptr& g : *all) names += (names.empty() ? "'" : ", '") + g->getName() + "'";
      throw DataError(path + ": " + std::to_string(all->size()) + " grids (" + names + ") and none named 'solid'");
    }
    meta = all->front();
  }
  const std::string what = path + ": grid '" + meta->getName() + "'";
  const auto check_kind = [&](const openvdb::GridBase& g) {
    if (!g.isType<openvdb::BoolGrid>() && !g.isType<openvdb::FloatGrid>())
      throw DataError(what + " holds " + g.valueType() + " values; voxel grids are bool grids or float fog volumes");
    if (g.getGridClass() == openvdb::GRID_LEVEL_SET)
      throw DataError(what + " is a level set (its inside is not stored as active voxels): convert it to a fog volume");
  };
  check_kind(*meta);
  const auto lo = meta->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const auto hi = meta->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
  if (lo && hi) check_extent(openvdb::Coord(lo->value()), openvdb::Coord(hi->value()), what);
  // The first grid of the name, as readGrid takes it; checked again as read.
  openvdb::GridBase::Ptr grid = file.readGrid(meta->getName());
  check_kind(*grid);
  const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
  if (!box.empty()) check_extent(box.min(), box.max(), what);
  return grid;
}

// The solid voxels of `base` (bool: active and true; float: active and above 0), by `visit(coord)`.
template <class Visit>
void for_each_solid(const openvdb::GridBase& base, Visit visit) {
  if (const auto* b = dynamic_cast<const openvdb::BoolGrid*>(&base)) {
    for (auto it = b->cbeginValueOn(); it; ++it) {
      if (!it.getValue()) continue;
      if (it.isVoxelValue()) visit(it.getCoord());
      else {
        const openvdb::CoordBBox box = it.getBoundingBox();  // an active tile: every voxel of it
        for (auto c = box.begin(); c; ++c) visit(*c);
      }
    }
    return;
  }
  const auto& f = static_cast<const openvdb::FloatGrid&>(base);
  for (auto it = f.cbeginValueOn(); it; ++it) {
    if (!(it.getValue() > 0.0f)) continue;
    if (it.isVoxelValue()) visit(it.getCoord());
    else {
      const openvdb::CoordBBox box = it.getBoundingBox();
      for (auto c = box.begin(); c; ++c) visit(*c);
    }
  }
}

// Side, box and index origin: habuffer's metadata, else the active voxels'
// bounding cube placed by the transform.
struct Placement {
  std::uint32_t n = 0;
  Bounds box;
  openvdb::Coord origin;  // the index of voxel (0, 0, 0)
};

Placement placement(const openvdb::GridBase& g, const std::string& path) {
  Placement p;
  const openvdb::CoordBBox active = g.evalActiveVoxelBoundingBox();
  if (g["habuffer_side"]) {
    const std::int32_t side = g.metaValue<openvdb::Int32>("habuffer_side");
    if (side < 1 || side > kMaxSide)
      throw DataError(path + ": habuffer_side " + std::to_string(side) + " is outside 1.." + std::to_string(kMaxSide));
    p.n = static_cast<std::uint32_t>(side);
    p.box.add(vec(g.metaValue<openvdb::Vec3s>("habuffer_box_lo")));
    p.box.add(vec(g.metaValue<openvdb::Vec3s>("habuffer_box_hi")));
    const openvdb::Coord a = active.min(), b = active.max();
    if (!active.empty() && (std::min({a.x(), a.y(), a.z()}) < 0 || std::max({b.x(), b.y(), b.z()}) >= side))
      throw DataError(path + ": active voxels lie outside the grid of side " + std::to_string(side) + " its metadata give");
    return p;
  }
  const openvdb::math::Transform& xf = g.transform();
  const openvdb::math::MapBase& map = *xf.baseMap();
  const bool scale_and_translation =
      map.isType<openvdb::math::ScaleTranslateMap>() || map.isType<openvdb::math::UniformScaleTranslateMap>() ||
      map.isType<openvdb::math::ScaleMap>() || map.isType<openvdb::math::UniformScaleMap>() ||
      map.isType<openvdb::math::TranslationMap>();
  if (!xf.isLinear() || !scale_and_translation)
    throw DataError(path + ": grid '" + g.getName() + "' has a " + xf.baseMap()->type() +
                    " transform; voxel grids take a scale and a translation only");
  if (active.empty()) throw DataError(path + ": grid '" + g.getName() + "' has no active voxels to place a grid around");
  const openvdb::Coord extent = active.dim();
  const int side = std::max({extent.x(), extent.y(), extent.z()});
  if (side > kMaxSide)
    throw DataError(path + ": grid '" + g.getName() + "' spans " + std::to_string(side) + " voxels; at most " +
                    std::to_string(kMaxSide));
  p.n = static_cast<std::uint32_t>(side);
  p.origin = active.min();
  const openvdb::Vec3d lo = xf.indexToWorld(openvdb::Vec3d(p.origin.asVec3d()) - openvdb::Vec3d(0.5));
  const openvdb::Vec3d hi = xf.indexToWorld(openvdb::Vec3d(p.origin.asVec3d()) + openvdb::Vec3d(p.n - 0.5));
  p.box.add({static_cast<float>(lo.x()), static_cast<float>(lo.y()), static_cast<float>(lo.z())});
  p.box.add({static_cast<float>(hi.x()), static_cast<float>(hi.y()), static_cast<float>(hi.z())});
  return p;
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

VoxelGrid load_voxel_vdb(const std::string& path) {
  initialize();
  try {
    openvdb::io::File file(path);
    file.open(false);  // no delayed loading: the file may change once we return
    const openvdb::GridBase::Ptr g = pick_grid(file, path);
    file.close();
    const Placement p = placement(*g, path);
    if (!(p.box.hi.x > p.box.lo.x && p.box.hi.y > p.box.lo.y && p.box.hi.z > p.box.lo.z))
      throw DataError(path + ": the voxel grid's box is empty or not finite");
    VoxelGrid out(p.n, p.box);
    for_each_solid(*g, [&](const openvdb::Coord& c) {
      const openvdb::Coord i = c - p.origin;
      out.set(static_cast<std::uint32_t>(i.x()), static_cast<std::uint32_t>(i.y()), static_cast<std::uint32_t>(i.z()));
    });
    return out;
  } catch (const openvdb::Exception& e) {
    throw DataError(path + ": not a readable OpenVDB file: " + e.what());
  }
}

}  // namespace habuffer
