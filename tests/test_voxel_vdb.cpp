// Voxel grids as OpenVDB files (habuffer/render/voxel_vdb.h): the round trip
// is exact; OpenVDB's own API, not our loader, sees the same active voxels
// where the mesh's cells are; grids written by other tools (a float fog
// volume, no habuffer metadata) are placed by their transform; what is no
// voxel grid is refused naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "habuffer/data_error.h"
#include "habuffer/render/voxel_vdb.h"

#ifdef HABUFFER_TEST_OPENVDB
#include <openvdb/openvdb.h>
#endif

namespace habuffer {
namespace {

class VdbFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!has_vdb_support()) GTEST_SKIP() << "built without OpenVDB: " << vdb_support();
    dir_ = std::filesystem::temp_directory_path() / ("habuffer_vdb_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  [[nodiscard]] std::string path(const char* name) const { return (dir_ / name).string(); }
  // Scattered voxels, and an 8^3 block that OpenVDB stores as one tile.
  static VoxelGrid grid() {
    Bounds box;
    box.add({-1.0f, 0.0f, 2.0f});
    box.add({1.5f, 4.0f, 3.25f});
    VoxelGrid g(20, box);
    for (std::uint32_t i = 0; i < 20; ++i) g.set(i, (i * 7) % 20, 19 - i);
    for (std::uint32_t z = 8; z < 16; ++z)
      for (std::uint32_t y = 8; y < 16; ++y)
        for (std::uint32_t x = 8; x < 16; ++x) g.set(x, y, z);
    return g;
  }
  std::filesystem::path dir_;
};

void expect_same(const VoxelGrid& a, const VoxelGrid& b) {
  ASSERT_EQ(a.n, b.n);
  EXPECT_EQ(a.box.lo, b.box.lo);
  EXPECT_EQ(a.box.hi, b.box.hi);
  EXPECT_EQ(a.words, b.words);
}

TEST_F(VdbFiles, AGridRoundTripsBitForBitThroughAVdbFileAndTheLoaderTellsTheFormatByItsBytes) {
  const VoxelGrid g = grid();
  save_voxel_vdb(path("g.vdb"), g, "a comment");
  expect_same(load_voxel_vdb(path("g.vdb")), g);
  EXPECT_TRUE(is_vdb_file(path("g.vdb")));
  // Named like the other format, read as what its bytes say; and the other way round.
  std::filesystem::copy_file(path("g.vdb"), path("g.vox"));
  expect_same(load_voxel_file(path("g.vox")), g);
  save_voxel_grid(path("h.vdb"), g);
  EXPECT_FALSE(is_vdb_file(path("h.vdb")));
  expect_same(load_voxel_file(path("h.vdb")), g);
  // An empty grid keeps its side and box.
  const VoxelGrid empty(3, g.box);
  save_voxel_vdb(path("e.vdb"), empty);
  expect_same(load_voxel_vdb(path("e.vdb")), empty);
}

TEST_F(VdbFiles, WhatIsNoVoxelGridIsRefusedNamingTheFileAndNothingIsLeftBehindByAFailedWrite) {
  std::ofstream(path("text.vdb")) << "not a vdb file at all";
  for (const char* name : {"text.vdb", "missing.vdb"}) {
    try {
      (void)load_voxel_vdb(path(name));
      ADD_FAILURE() << name << " was read";
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(save_voxel_vdb(path("no/such/dir/g.vdb"), grid()), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path("no")));
}

#ifdef HABUFFER_TEST_OPENVDB

// Writes `grids` with OpenVDB's API alone.
void write_vdb(const std::string& file, openvdb::GridPtrVec grids) {
  openvdb::initialize();
  openvdb::io::File f(file);
  f.write(grids);
  f.close();
}

TEST_F(VdbFiles, OpenVdbsOwnReaderSeesTheSameActiveVoxelsAtTheCentresOfTheMeshsCells) {
  const VoxelGrid g = grid();
  save_voxel_vdb(path("g.vdb"), g);
  openvdb::initialize();
  openvdb::io::File f(path("g.vdb"));
  f.open();
  const auto solid = openvdb::gridPtrCast<openvdb::BoolGrid>(f.readGrid("solid"));
  f.close();
  ASSERT_TRUE(solid);
  EXPECT_EQ(solid->activeVoxelCount(), g.count());
  std::uint64_t seen = 0;
  for (std::uint32_t z = 0; z < g.n; ++z)
    for (std::uint32_t y = 0; y < g.n; ++y)
      for (std::uint32_t x = 0; x < g.n; ++x) {
        const openvdb::Coord c(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z));
        const bool on = solid->tree().isValueOn(c) && solid->tree().getValue(c);
        ASSERT_EQ(on, g.solid(x, y, z)) << x << "," << y << "," << z;
        seen += on ? 1 : 0;
      }
  EXPECT_EQ(seen, g.count());
  // Voxel (x, y, z) stands at the centre of its cell of the box.
  const glm::dvec3 lo(g.box.lo), cell = (glm::dvec3(g.box.hi) - lo) / static_cast<double>(g.n);
  for (const openvdb::Coord c : {openvdb::Coord(0, 0, 0), openvdb::Coord(19, 3, 7)}) {
    const openvdb::Vec3d w = solid->transform().indexToWorld(c);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(w[a], lo[a] + (c[a] + 0.5) * cell[a], 1e-6) << "axis " << a;
  }
}

TEST_F(VdbFiles, AFogVolumeWithoutOurMetadataIsTheBoundingCubeOfItsVoxelsPlacedByItsTransform) {
  openvdb::FloatGrid::Ptr fog = openvdb::FloatGrid::create(0.0f);
  fog->setName("density");
  fog->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(1.0);
  xf->preScale(openvdb::Vec3d(0.5, 0.25, 2.0));
  xf->postTranslate(openvdb::Vec3d(10.0, 20.0, 30.0));
  fog->setTransform(xf);
  fog->tree().setValue(openvdb::Coord(-2, 5, 1), 0.7f);
  fog->tree().setValue(openvdb::Coord(1, 5, 1), 0.1f);
  fog->tree().setValue(openvdb::Coord(0, 6, 2), 0.0f);  // active, but no density: not solid
  write_vdb(path("fog.vdb"), {fog});
  const VoxelGrid g = load_voxel_vdb(path("fog.vdb"));
  ASSERT_EQ(g.n, 4u);  // x spans -2..1: the bounding cube's side
  EXPECT_EQ(g.count(), 2u);
  EXPECT_TRUE(g.solid(0, 0, 0));
  EXPECT_TRUE(g.solid(3, 0, 0));
  EXPECT_FLOAT_EQ(g.box.lo.x, 10.0f + (-2 - 0.5f) * 0.5f);
  EXPECT_FLOAT_EQ(g.box.lo.y, 20.0f + (5 - 0.5f) * 0.25f);
  EXPECT_FLOAT_EQ(g.box.hi.z, 30.0f + (1 + 3.5f) * 2.0f);
}

TEST_F(VdbFiles, LevelSetsOtherTypesRotationsAmbiguousFilesAndHugeGridsAreRefusedSayingWhy) {
  const auto refused = [&](const char* name, openvdb::GridPtrVec grids, const char* why) {
    write_vdb(path(name), std::move(grids));
    try {
      (void)load_voxel_vdb(path(name));
      ADD_FAILURE() << name << " was read";
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  openvdb::FloatGrid::Ptr level_set = openvdb::FloatGrid::create(1.0f);
  level_set->setGridClass(openvdb::GRID_LEVEL_SET);
  level_set->tree().setValue(openvdb::Coord(0, 0, 0), -1.0f);
  refused("level_set.vdb", {level_set}, "level set");
  openvdb::Vec3SGrid::Ptr vectors = openvdb::Vec3SGrid::create();
  vectors->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1.0f));
  refused("vectors.vdb", {vectors}, "vec3s");
  openvdb::BoolGrid::Ptr a = openvdb::BoolGrid::create(false), b = openvdb::BoolGrid::create(false);
  a->setName("a");
  b->setName("b");
  a->tree().setValue(openvdb::Coord(0, 0, 0), true);
  b->tree().setValue(openvdb::Coord(0, 0, 0), true);
  refused("two.vdb", {a, b}, "none named 'solid'");
  openvdb::BoolGrid::Ptr rotated = openvdb::BoolGrid::create(false);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(1.0);
  xf->preRotate(0.5, openvdb::math::Z_AXIS);
  rotated->setTransform(xf);
  rotated->tree().setValue(openvdb::Coord(0, 0, 0), true);
  refused("rotated.vdb", {rotated}, "scale and a translation");
  openvdb::BoolGrid::Ptr huge = openvdb::BoolGrid::create(false);
  huge->tree().setValue(openvdb::Coord(0, 0, 0), true);
  huge->tree().setValue(openvdb::Coord(5000, 0, 0), true);
  refused("huge.vdb", {huge}, "at most 4096");
}

#endif  // HABUFFER_TEST_OPENVDB

}  // namespace
}  // namespace habuffer
