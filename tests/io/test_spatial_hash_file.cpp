// Files of the spatial hash (habuffer/spatial_hash_file.h): key CSVs, and the
// table saved and loaded bit for bit, with every corruption refused naming
// what is wrong.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "habuffer/csv.h"
#include "habuffer/key_streams.h"
#include "habuffer/spatial_hash_file.h"

namespace habuffer::spatial {
namespace {

class SpatialHashFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("habuffer_spatial_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  [[nodiscard]] std::string path(const char* name) const { return (dir_ / name).string(); }
  void write(const char* name, const std::string& text) const { std::ofstream(path(name), std::ios::binary) << text; }
  [[nodiscard]] std::string bytes(const char* name) const {
    std::ifstream in(path(name), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::filesystem::path dir_;
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const DataError& e) {
    return e.what();
  }
  return "accepted";
}

TEST_F(SpatialHashFiles, KeyFilesOfEachHeaderAreReadAndBadRowsNamed) {
  write("a.csv", "x,y\n1,2\n3,4\n");
  write("b.csv", "x, y, z, value\n1,2,3,0xff\n");
  write("c.csv", "x,y,value\n5,6,7\n");
  const KeyFile a = read_keys_csv(path("a.csv"));
  EXPECT_EQ(a.keys, (std::vector<glm::uvec3>{{1, 2, 0}, {3, 4, 0}}));
  EXPECT_TRUE(a.values.empty());
  const KeyFile b = read_keys_csv(path("b.csv"));
  EXPECT_TRUE(b.three_d);
  EXPECT_EQ(b.values, std::vector<std::uint32_t>{255});
  EXPECT_EQ(read_keys_csv(path("c.csv")).values, std::vector<std::uint32_t>{7});
  EXPECT_EQ(domain_of(a.keys), (Domain{4, 5, 1}));
  write("d.csv", "x,y\n1,-2\n");
  EXPECT_NE(error_of([&] { (void)read_keys_csv(path("d.csv")); }).find("d.csv:2: field y"), std::string::npos);
  write("e.csv", "u,v\n1,2\n");
  EXPECT_NE(error_of([&] { (void)read_keys_csv(path("e.csv")); }).find("e.csv"), std::string::npos);
  write("f.csv", "x,y\n1,2,3\n");
  EXPECT_NE(error_of([&] { (void)read_keys_csv(path("f.csv")); }).find("f.csv:2"), std::string::npos);
}

TEST_F(SpatialHashFiles, ATableIsSavedAndLoadedBitForBitAndCorruptionIsRefused) {
  KeySetOptions o;
  o.set = KeySet::VoxelShell;
  o.domain = {40, 40, 40};
  const std::vector<glm::uvec3> keys = make_keys(o);
  SpatialHashConfig c;
  c.domain = o.domain;
  c.rule = DuplicateRule::Min;
  c.threads = 1;
  SpatialHash h(c);
  std::vector<std::uint32_t> values(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) values[i] = static_cast<std::uint32_t>(i * 31);
  h.insert(keys, values);
  h.erase(keys[3]);
  save_spatial_hash(path("t.tab"), h);
  const SpatialHash back = load_spatial_hash(path("t.tab"));
  EXPECT_TRUE(std::equal(back.table().begin(), back.table().end(), h.table().begin(), h.table().end()));
  EXPECT_EQ(back.size(), h.size());
  EXPECT_EQ(back.stats().tombstones, 1u);
  EXPECT_EQ(back.find(keys[10]), 310u);
  EXPECT_FALSE(back.contains(keys[3]));

  const std::string good = bytes("t.tab");
  const auto corrupt = [&](std::size_t at, std::uint64_t word, int size) {
    std::string b = good;
    std::memcpy(b.data() + at, &word, static_cast<std::size_t>(size));
    write("x.tab", b);
    return error_of([&] { (void)load_spatial_hash(path("x.tab")); });
  };
  constexpr std::size_t kSlots = 56;
  std::size_t used = 0;
  while (h.table()[used] == 0 || ((h.table()[used] >> 32) & 1u) == 0u) ++used;
  EXPECT_NE(corrupt(0, 0x5858585858585858ull, 8).find("not a spatial hash table"), std::string::npos);
  EXPECT_NE(corrupt(8, 0, 4).find("zero side"), std::string::npos);           // domain x 0
  EXPECT_NE(corrupt(20, 9, 4).find("duplicate rule 9"), std::string::npos);
  EXPECT_NE(corrupt(40, 100000, 4).find("bytes"), std::string::npos);       // table x
  // A record at the last age (beyond its max-age cell, or naming a key
  // outside the domain). (A record moved by one age can be another key's,
  // placed where a lookup finds it: a table of other keys, not a broken one.)
  const std::uint64_t r = h.table()[used];
  const std::string moved = corrupt(kSlots + used * 8, r | (std::uint64_t{0xFF} << 56), 8);
  EXPECT_NE(moved.find("slot " + std::to_string(used)), std::string::npos) << moved;
  // A record of age 0 (not a record at all).
  EXPECT_NE(corrupt(kSlots + used * 8, r & 0x00FFFFFFFFFFFFFFull, 8).find("age 0"), std::string::npos);
  std::string truncated = good.substr(0, good.size() - 4);
  write("y.tab", truncated);
  EXPECT_NE(error_of([&] { (void)load_spatial_hash(path("y.tab")); }).find("bytes"), std::string::npos);
}

TEST(KeySets, SparseImageKeysOnSmallDomainsStayInsideTheDomainAndReachTheCoverage) {
  // Discs near the border of a small domain start or end off it (the
  // generator once cast a negative column to uint32 and wrote past its bitmap).
  for (const std::uint32_t side : {1u, 2u, 3u, 5u, 10u, 64u})
    for (const double coverage : {0.1, 0.5, 0.9})
      for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        KeySetOptions o;
        o.set = KeySet::SparseImage;
        o.domain = {side, side + 1, 1};
        o.coverage = coverage;
        o.seed = seed;
        const std::vector<glm::uvec3> keys = make_keys(o);
        const double cells = static_cast<double>(side) * (side + 1);
        EXPECT_GE(static_cast<double>(keys.size()), coverage * cells) << side << " " << coverage << " " << seed;
        EXPECT_LE(static_cast<double>(keys.size()), cells);
        for (const glm::uvec3& k : keys) {
          ASSERT_LT(k.x, side);
          ASSERT_LT(k.y, side + 1);
          ASSERT_EQ(k.z, 0u);
        }
      }
}

}  // namespace
}  // namespace habuffer::spatial
