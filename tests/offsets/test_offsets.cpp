// SPEC 3: offset generators and offset lists.
#include <gtest/gtest.h>

#include <set>

#include "habuffer/offset_sequence.h"

namespace habuffer {
namespace {

std::set<std::uint64_t> distinct(const OffsetSequence& o, Extent table) {
  std::set<std::uint64_t> s;
  for (auto v : o.values()) s.insert(v.x + std::uint64_t{v.y} * table.x);
  return s;
}

class Generators : public ::testing::TestWithParam<OffsetGenerator> {};

TEST_P(Generators, AreDeterministicInsideTheTableAndPairwiseDistinct) {
  for (Extent table : {Extent{1024, 768}, Extent{17, 15}, Extent{300, 1}, Extent{1, 300}}) {
    const auto a = OffsetSequence::make(GetParam(), table, 255, 9);
    const auto b = OffsetSequence::make(GetParam(), table, 255, 9);
    ASSERT_EQ(a.size(), 255u);
    EXPECT_TRUE(std::equal(a.values().begin(), a.values().end(), b.values().begin()));
    for (auto v : a.values()) {
      EXPECT_LT(v.x, table.x);
      EXPECT_LT(v.y, table.y);
    }
    EXPECT_EQ(distinct(a, table).size(), 255u) << table.str();
    const auto c = OffsetSequence::make(GetParam(), table, 255, 10);
    EXPECT_FALSE(std::equal(a.values().begin(), a.values().end(), c.values().begin())) << "seed must matter";
  }
}

TEST_P(Generators, RepeatCyclicallyOnTablesSmallerThanAmax) {
  const Extent table{5, 3};  // 15 slots < 255 ages
  const auto o = OffsetSequence::make(GetParam(), table, 255, 3);
  EXPECT_EQ(distinct(o, table).size(), 15u);
  for (std::size_t i = 15; i < o.size(); ++i) EXPECT_EQ(o[i], o[i % 15]);
}

INSTANTIATE_TEST_SUITE_P(Offsets, Generators, ::testing::Values(OffsetGenerator::Random, OffsetGenerator::Farthest));

// Brute force on a small torus: each farthest offset maximizes the minimum
// toroidal distance to all earlier ones, ties going to the smallest slot.
TEST(FarthestOffsets, EachOffsetIsTheGreedyMaxMinChoice) {
  for (Extent table : {Extent{37, 23}, Extent{64, 64}, Extent{40, 7}}) {
    const auto o = OffsetSequence::farthest(table, 120, 5);
    for (std::size_t k = 1; k < o.size(); ++k) {
      std::uint64_t best = 0, best_slot = 0;
      for (std::uint32_t y = 0; y < table.y; ++y)
        for (std::uint32_t x = 0; x < table.x; ++x) {
          std::uint64_t d = UINT64_MAX;
          for (std::size_t j = 0; j < k; ++j) d = std::min(d, toroidal_distance2({x, y}, o[j], table));
          if (d > best) {
            best = d;
            best_slot = x + std::uint64_t{y} * table.x;
          }
        }
      ASSERT_EQ(o[k].x + std::uint64_t{o[k].y} * table.x, best_slot) << table.str() << " offset " << k;
    }
  }
}

// Quality: the farthest sequence's minimum pairwise distance dominates random
// offsets' for every prefix (deterministic seeds; the margin is large, as the
// greedy keeps every prefix near-optimally spread).
TEST(FarthestOffsets, SpreadEveryPrefixWiderThanRandomOffsets) {
  const Extent table{1024, 1024};
  const auto far = min_pairwise_distances(OffsetSequence::farthest(table, 255, 1).values(), table);
  const auto rnd = min_pairwise_distances(OffsetSequence::random(table, 255, 1).values(), table);
  for (std::size_t i = 0; i < far.size(); ++i) EXPECT_GT(far[i], rnd[i]) << "k = " << i + 2;
  // 255 points on a 1024^2 torus: hexagonal packing would allow ~68; greedy gets over half of that.
  EXPECT_GT(far.back(), 34.0);
}

TEST(OffsetList, AcceptsValidRowsAndRejectsBadOnesNamingTheRow) {
  const Extent table{8, 8};
  std::vector<glm::uvec2> rows;
  for (std::uint32_t i = 0; i < 15; ++i) rows.emplace_back(i % 8, i / 8);
  EXPECT_NO_THROW(OffsetSequence::from_list(table, 15, rows));
  EXPECT_THROW(OffsetSequence::from_list(table, 16, rows), std::invalid_argument);  // too short
  auto outside = rows;
  outside[3] = {8, 0};
  try {
    OffsetSequence::from_list(table, 15, outside);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside table 8x8"), std::string::npos) << e.what();
  }
  auto dup = rows;
  dup[9] = dup[2];
  try {
    OffsetSequence::from_list(table, 15, dup);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("duplicate"), std::string::npos) << e.what();
  }
}

TEST(OffsetList, SmallTableNeedsCyclicRows) {
  const Extent table{2, 2};
  std::vector<glm::uvec2> rows{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const auto o = OffsetSequence::from_list(table, 15, rows);  // four rows suffice, extended cyclically
  EXPECT_EQ(o[13], o[1]);
  rows.insert(rows.end(), {{0, 0}, {1, 1}});  // row 6 should repeat row 2
  EXPECT_THROW(OffsetSequence::from_list(table, 15, rows), std::invalid_argument);
}

TEST(FarthestOffsets, RefusesTablesAboveTheDistanceFieldLimit) {
  EXPECT_THROW(OffsetSequence::farthest({1u << 15, 1u << 14}, 255, 1), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
