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

// The grid `load_voxel_vdb` reads: "solid", or the only one.
openvdb::GridBase::Ptr pick_grid(openvdb::io::File& file, const std::string& path) {
  const openvdb::GridPtrVecPtr all = file.readAllGridMetadata();
  if (all->empty()) throw DataError(path + ": the OpenVDB file holds no grid");
  openvdb::GridBase::Ptr meta;
  for (const openvdb::GridBase::Ptr& g : *all)
    if (g->getName() == kGridName) meta = g;
  if (!meta) {
    if (all->size() != 1) {
      std::string names;
      for (const openvdb::GridBase::Ptr& g : *all) names += (names.empty() ? "'" : ", '") + g->getName() + "'";
      throw DataError(path + ": " + std::to_string(all->size()) + " grids (" + names + ") and none named 'solid'");
    }
    meta = all->front();
  }
  if (!meta->isType<openvdb::BoolGrid>() && !meta->isType<openvdb::FloatGrid>())
    throw DataError(path + ": grid '" + meta->getName() + "' holds " + meta->valueType() +
                    " values; voxel grids are bool grids or float fog volumes");
  if (meta->getGridClass() == openvdb::GRID_LEVEL_SET)
    throw DataError(path + ": grid '" + meta->getName() +
                    "' is a level set (its inside is not stored as active voxels): convert it to a fog volume");
  // The active voxels' box, from the file's metadata, before any voxel is read.
  const openvdb::Vec3i lo = meta->metaValue<openvdb::Vec3i>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const openvdb::Vec3i hi = meta->metaValue<openvdb::Vec3i>(openvdb::GridBase::META_FILE_BBOX_MAX);
  for (int a = 0; a < 3; ++a)
    if (static_cast<std::int64_t>(hi[a]) - lo[a] >= kMaxSide)
      throw DataError(path + ": grid '" + meta->getName() + "' spans " +
                      std::to_string(static_cast<std::int64_t>(hi[a]) - lo[a] + 1) + " voxels along an axis; at most " +
                      std::to_string(kMaxSide));
  const openvdb::Index64 voxels = meta->metaValue<openvdb::Int64>(openvdb::GridBase::META_FILE_VOXEL_COUNT);
  try {
    check_fits_in_memory(path + ": " + std::to_string(voxels) + " active voxels", voxels * 16);
  } catch (const std::invalid_argument& e) {
    throw DataError(e.what());
  }
  return file.readGrid(meta->getName());
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
  p.n = static_cast<std::uint32_t>(std::max({extent.x(), extent.y(), extent.z()}));
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
