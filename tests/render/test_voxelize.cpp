// Solid voxelization on sorted depth lists (habuffer/render/voxelizer.h):
// exact fills of boxes, touching solids, merged crossings reported, and no
// mismatch against the ray-parity reference outside the near-surface band.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <unistd.h>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <thread>

#include "gl_test_support.h"
#include "habuffer/data_error.h"
#include "habuffer/harness/voxel_figure.h"
#include "habuffer/render/voxelizer.h"
#include "habuffer/solids.h"

namespace habuffer {
namespace {

using test::gl_context;

Scene scene_of(std::vector<Mesh> meshes) {
  Scene s;
  s.name = "solids";
  s.meshes = std::move(meshes);
  return s;
}

Bounds unit_box() {
  Bounds b;
  b.add({0.0f, 0.0f, 0.0f});
  b.add({1.0f, 1.0f, 1.0f});
  return b;
}

// Voxels that differ from the reference outside its band, and the band's size.
std::pair<std::uint64_t, std::uint64_t> mismatches(const Scene& scene, const VoxelizeSettings& s, const VoxelGrid& got) {
  std::vector<bool> band;
  const VoxelGrid want = voxel_reference(scene, s, &band);
  std::uint64_t wrong = 0, in_band = 0;
  for (std::uint32_t z = 0; z < s.grid; ++z)
    for (std::uint32_t y = 0; y < s.grid; ++y)
      for (std::uint32_t x = 0; x < s.grid; ++x) {
        const std::uint64_t i = x + std::uint64_t{s.grid} * (y + std::uint64_t{s.grid} * z);
        if (band[i]) {
          ++in_band;
          continue;
        }
        wrong += got.solid(x, y, z) != want.solid(x, y, z);
      }
  return {wrong, in_band};
}

TEST(Voxelize, ABoxFillingTheGridGivesEveryVoxelAndHalfABoxHalfOfThemAlongEveryAxis) {
  gl_context();
  const std::uint32_t n = 16;
  for (const VoxelAxis axis : {VoxelAxis::X, VoxelAxis::Y, VoxelAxis::Z}) {
    SCOPED_TRACE(to_string(axis));
    VoxelizeSettings s;
    s.grid = n;
    s.axis = axis;
    const Voxelization full = voxelize(scene_of({box_mesh({0, 0, 0}, {1, 1, 1})}), s);
    EXPECT_EQ(full.grid.count(), std::uint64_t{n} * n * n);
    EXPECT_EQ(full.stats.counters.failures(), 0u);
    s.box = unit_box();
    const Voxelization half = voxelize(scene_of({box_mesh({0, 0, 0}, {1, 1, 0.5f})}), s);
    EXPECT_EQ(half.grid.count(), std::uint64_t{n} * n * n / 2);
    for (std::uint32_t z = 0; z < n; ++z) EXPECT_EQ(half.grid.solid(3, 5, z), z < n / 2) << "z " << z;
  }
}

TEST(Voxelize, TwoBoxesSharingAFaceFillTheGridAndCoincidentFacesAreReportedAsMerged) {
  gl_context();
  VoxelizeSettings s;
  s.grid = 16;
  s.axis = VoxelAxis::X;  // across the shared face: one box's exit and the other's entry at one depth
  const Voxelization touching =
      voxelize(scene_of({box_mesh({0, 0, 0}, {0.5f, 1, 1}), box_mesh({0.5f, 0, 0}, {1, 1, 1})}), s);
  EXPECT_EQ(touching.grid.count(), 16u * 16u * 16u);
  EXPECT_EQ(touching.stats.merged, 0u);  // an exit and an entry: two records, different facings
  const Voxelization doubled = voxelize(scene_of({box_mesh({0, 0, 0}, {1, 1, 1}), box_mesh({0, 0, 0}, {1, 1, 1})}), s);
  EXPECT_GT(doubled.stats.merged, 0u);  // equal crossings (same facing, same code) merged and counted
}

// cuda_voxelizer's users found a cube at grid 8 coming out 8x8x7; a sheet
// thinner than a depth code has its entry and exit at one code, two records
// of opposite facing: no voxel between them, nothing merged, no odd column.
TEST(Voxelize, ACubeAtGridEightIsEightCubedAndASheetThinnerThanACodeHasNoVoxel) {
  gl_context();
  for (const std::uint32_t n : {8u, 7u, 1u}) {
    VoxelizeSettings s;
    s.grid = n;
    EXPECT_EQ(voxelize(scene_of({box_mesh({-1, -1, -1}, {1, 1, 1})}), s).grid.count(), std::uint64_t{n} * n * n);
  }
  VoxelizeSettings s;
  s.grid = 16;
  s.box = unit_box();
  // z from 0.25 to the next float32: half a depth code (2^-24 of the box) thick.
  const float top = std::nextafter(0.25f, 1.0f);
  const Voxelization sheet = voxelize(scene_of({box_mesh({0.1f, 0.1f, 0.25f}, {0.9f, 0.9f, top})}), s);
  EXPECT_EQ(sheet.grid.count(), 0u);
  EXPECT_EQ(sheet.stats.merged, 0u);
  EXPECT_EQ(sheet.stats.odd_columns, 0u);
  EXPECT_GT(sheet.stats.counters.stored(), 0u);
}

TEST(Voxelize, ASphereAndATorusMatchTheRayParityReferenceOutsideTheNearSurfaceBand) {
  gl_context();
  for (const bool torus : {false, true}) {
    const Scene scene = scene_of({torus ? torus_mesh({0, 0, 0}, 1.0f, 0.4f) : sphere_mesh({0, 0, 0}, 1.0f)});
    for (const VoxelAxis axis : {VoxelAxis::X, VoxelAxis::Z}) {
      SCOPED_TRACE(std::string(torus ? "torus " : "sphere ") + to_string(axis));
      VoxelizeSettings s;
      s.grid = 32;
      s.axis = axis;
      const Voxelization v = voxelize(scene, s);
      const auto [wrong, band] = mismatches(scene, s, v.grid);
      EXPECT_EQ(wrong, 0u);
      EXPECT_LT(band, 32u * 32u * 32u / 20);
      EXPECT_GT(v.grid.count(), 32u * 32u * 32u / 10);
    }
  }
}

// Three-axis voting against the same vote of the three references: a torus
// (watertight: every axis agrees) and a box missing its top face (each axis
// that sees the hole is wrong, the vote over the other two is not).
TEST(Voxelize, AThreeAxisVoteMatchesTheVoteOfTheThreeReferences) {
  gl_context();
  Mesh open_box = box_mesh({-1, -1, -1}, {1, 1, 1});
  open_box.indices.resize(open_box.indices.size() - 6);  // one face gone
  for (const Mesh& m : {torus_mesh({0, 0, 0}, 1.0f, 0.4f), open_box}) {
    SCOPED_TRACE(m.name);
    const Scene scene = scene_of({m});
    VoxelizeSettings s;
    s.grid = 20;
    const Voxelization v = voxelize_voting(scene, s);
    const VoxelCheck c = check_voxels_voting(scene, s, v.grid);
    EXPECT_EQ(c.mismatches, 0u);
    EXPECT_LT(c.band, 20u * 20u * 20u / 10);
    EXPECT_GT(v.grid.count(), 20u * 20u * 20u / 10);
  }
}

// The CPU path (GL rasterizes and captures, the CPU builds the lists): the
// same crossings, so the same grid as the GPU's, voxel for voxel.
TEST(Voxelize, TheCpuAndGlPathsGiveTheSameGrid) {
  gl_context();
  const Scene scene = scene_of({torus_mesh({0, 0, 0}, 1.0f, 0.4f), box_mesh({-0.2f, -0.2f, -0.2f}, {0.2f, 0.2f, 0.2f})});
  for (const VoxelAxis axis : {VoxelAxis::X, VoxelAxis::Z}) {
    SCOPED_TRACE(to_string(axis));
    VoxelizeSettings s;
    s.grid = 24;
    s.axis = axis;
    const Voxelization gl = voxelize(scene, s);
    s.cpu = true;
    s.threads = 2;
    const Voxelization cpu = voxelize(scene, s);
    EXPECT_EQ(gl.grid.words, cpu.grid.words);
    EXPECT_EQ(gl.stats.counters, cpu.stats.counters);
    EXPECT_GT(cpu.grid.count(), 0u);
  }
}

TEST(Voxelize, TheFiguresTableHasOneRowPerMeshAndGridWithNoMismatchOnABox) {
  gl_context();
  harness::VoxelFigureSettings f;
  f.meshes = {"box", "torus"};
  f.grids = {8, 16};
  f.repeats = 1;
  const harness::ResultTable t = harness::run_voxel_figure(f);
  ASSERT_EQ(t.rows.size(), 4u);
  for (const harness::ResultRow& r : t.rows) EXPECT_EQ(r.number("mismatches"), 0.0);
  EXPECT_EQ(t.rows[1].number("voxels"), 16.0 * 16 * 16);  // the box fills its grid
  EXPECT_GT(t.rows[3].number("voxels"), 0.0);
  f.grids = {};
  EXPECT_THROW((void)harness::run_voxel_figure(f), std::invalid_argument);
}

TEST(Voxelize, BadSettingsAreRefusedNamingTheField) {
  gl_context();
  const Scene scene = scene_of({box_mesh({0, 0, 0}, {1, 1, 1})});
  VoxelizeSettings s;
  s.grid = 0;
  try {
    (void)voxelize(scene, s);
    ADD_FAILURE() << "grid 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--grid 0"), std::string::npos) << e.what();
  }
  s.grid = 8;
  Bounds small;
  small.add({0, 0, 0});
  small.add({0.5f, 0.5f, 0.5f});
  s.box = small;
  EXPECT_THROW((void)voxelize(scene, s), std::invalid_argument);
  EXPECT_THROW((void)voxelize(scene_of({}), VoxelizeSettings{}), SceneError);
  EXPECT_THROW((void)box_mesh({0, 0, 0}, {1, 0, 1}), std::invalid_argument);
  EXPECT_THROW((void)torus_mesh({0, 0, 0}, 0.5f, 0.5f), std::invalid_argument);
}

// Files: the HAVOXEL1 grid round-trips bit for bit and refuses what is not
// one; the NRRD copy's header places the grid in the mesh's space and its
// bytes are the grid's voxels, x fastest.
class VoxelFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("habuffer_voxels_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  [[nodiscard]] std::string path(const char* name) const { return (dir_ / name).string(); }
  static VoxelGrid diagonal_grid() {
    Bounds box;
    box.add({-1.0f, 0.0f, 2.0f});
    box.add({1.0f, 4.0f, 3.0f});
    VoxelGrid g(5, box);
    for (std::uint32_t i = 0; i < 5; ++i) g.set(i, (i * 2) % 5, 4 - i);
    g.set(4, 0, 0);
    return g;
  }
  std::filesystem::path dir_;
};

TEST_F(VoxelFiles, TheGridFileRoundTripsAndRefusesATruncatedOrForeignFile) {
  const VoxelGrid g = diagonal_grid();
  save_voxel_grid(path("g.vox"), g);
  const VoxelGrid back = load_voxel_grid(path("g.vox"));
  EXPECT_EQ(back.n, 5u);
  EXPECT_EQ(back.words, g.words);
  EXPECT_EQ(back.box.lo, g.box.lo);
  EXPECT_EQ(back.box.hi, g.box.hi);
  std::filesystem::resize_file(path("g.vox"), std::filesystem::file_size(path("g.vox")) - 1);
  EXPECT_THROW((void)load_voxel_grid(path("g.vox")), std::runtime_error);  // DataError, naming the path
  std::ofstream(path("x.vox")) << "NRRD0004\n";
  EXPECT_THROW((void)load_voxel_grid(path("x.vox")), std::runtime_error);  // DataError, naming the path
  EXPECT_THROW((void)load_voxel_grid(path("missing.vox")), std::runtime_error);  // DataError, naming the path
  // A padding bit of the last word set (side 5: 125 voxels in two words):
  // a voxel outside the grid, refused naming it (fuzz_voxel_file found it).
  save_voxel_grid(path("g.vox"), g);
  std::string bytes;
  {
    std::ifstream in(path("g.vox"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  bytes.back() = static_cast<char>(bytes.back() | 0x80);  // bit 127 of the last little-endian word
  try {
    (void)parse_voxel_grid(bytes, "p.vox");
    ADD_FAILURE() << "a padding bit was taken";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("p.vox: the voxel grid sets padding bits past its 125 voxels"),
              std::string::npos)
        << e.what();
  }
}

// Issue 34: the grid loader read a directory into "basic_filebuf::underflow"
// and /dev/zero until memory ran out; both are refused by name before
// anything is read, and a pipe is still read whole.
TEST_F(VoxelFiles, TheGridLoaderRefusesDirectoriesAndDevicesAndReadsAPipe) {
  const auto message = [](const std::string& p) {
    try {
      (void)load_voxel_grid(p);
    } catch (const DataError& e) {
      return std::string(e.what());
    } catch (const std::exception& e) {
      return "not a DataError: " + std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string directory = message(dir_.string());
  ASSERT_NE(directory.find(": is a directory, not a voxel grid"), std::string::npos) << directory;  // before /dev/zero
  EXPECT_NE(message("/dev/zero").find("/dev/zero: is a device"), std::string::npos);
  const VoxelGrid g = diagonal_grid();
  save_voxel_grid(path("g.vox"), g);
  std::ifstream in(path("g.vox"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(::mkfifo(path("pipe.vox").c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(path("pipe.vox"), std::ios::binary) << bytes; });
  VoxelGrid back;
  const std::string why = [&] {
    try {
      back = load_voxel_grid(path("pipe.vox"));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  writer.join();
  EXPECT_EQ(why, "");
  EXPECT_EQ(back.words, g.words);
}

TEST_F(VoxelFiles, TheNrrdHeaderPlacesTheGridAndItsBytesAreTheVoxelsXFastest) {
  const VoxelGrid g = diagonal_grid();
  save_voxel_nrrd(path("g.nrrd"), g, "two\nlines");
  std::ifstream in(path("g.nrrd"), std::ios::binary);
  std::map<std::string, std::string> fields;
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "NRRD0004");
  std::vector<std::string> comments;
  while (std::getline(in, line) && !line.empty()) {
    if (line[0] == '#') {
      comments.push_back(line);
      continue;
    }
    const auto colon = line.find(": ");
    ASSERT_NE(colon, std::string::npos) << line;
    fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  EXPECT_EQ(comments.front(), "# two lines");  // the newline cannot end the header early
  EXPECT_EQ(fields["type"], "uint8");
  EXPECT_EQ(fields["dimension"], "3");
  EXPECT_EQ(fields["sizes"], "5 5 5");
  EXPECT_EQ(fields["encoding"], "raw");
  EXPECT_EQ(fields["space directions"], "(0.4,0,0) (0,0.8,0) (0,0,0.2)");  // the voxel's size per axis
  double ox = 0, oy = 0, oz = 0;
  ASSERT_EQ(std::sscanf(fields["space origin"].c_str(), "(%lf,%lf,%lf)", &ox, &oy, &oz), 3);
  EXPECT_NEAR(ox, -0.8, 1e-6);  // voxel (0, 0, 0)'s centre
  EXPECT_NEAR(oy, 0.4, 1e-6);
  EXPECT_NEAR(oz, 2.1, 1e-6);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(data.size(), 125u);
  for (std::uint32_t z = 0; z < 5; ++z)
    for (std::uint32_t y = 0; y < 5; ++y)
      for (std::uint32_t x = 0; x < 5; ++x)
        EXPECT_EQ(data[x + 5 * (y + 5 * z)], g.solid(x, y, z) ? 1 : 0) << x << " " << y << " " << z;
}

}  // namespace
}  // namespace habuffer
