// SPEC 4-6: probing, age equivalence, insertion outcomes, max-age table.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "habuffer/hash_kernel.h"
#include "test_support.h"

namespace habuffer {
namespace {

// A 4x4 screen on a 4x4 table with offsets O[i] = (i mod 4, i / 4): easy to trace.
HaBuffer traced_buffer(std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT, std::uint32_t block = 2) {
  BufferConfig c = test::config({4, 4}, {4, 4}, Layout::L64, 4, block);
  c.iter_limit = iter_limit;
  std::vector<glm::uvec2> rows;
  for (std::uint32_t i = 0; i < 15; ++i) rows.emplace_back(i % 4, i / 4);
  return HaBuffer(c, OffsetSequence::from_list(c.table, 15, rows));
}

std::uint64_t slot_of(std::uint32_t x, std::uint32_t y) { return x + 4u * y; }

TEST(Insert, FirstFragmentTakesItsAgeOneSlot) {
  HaBuffer b = traced_buffer();
  EXPECT_EQ(b.insert_one({1, 2, 0.5f, 0xAABBCCDDu}), HABUFFER_STORED);
  const RecordLayout& l = b.record_layout();
  EXPECT_EQ(b.slot(slot_of(1, 2)), l.pack(1, l.depth_code(0.5f), 0xAABBCCDDu));  // O[0] = (0,0)
  EXPECT_EQ(b.max_age().at(0, 1), 1u);
  EXPECT_EQ(b.count_stored(), 1u);
}

TEST(Insert, NearerFragmentEvictsFartherOneOfItsPixelWhichMovesToTheNextAge) {
  HaBuffer b = traced_buffer();
  const RecordLayout& l = b.record_layout();
  b.insert_one({0, 0, 0.75f, 1});
  EXPECT_EQ(b.insert_one({0, 0, 0.25f, 2}), HABUFFER_STORED);
  EXPECT_EQ(b.slot(slot_of(0, 0)), l.pack(1, l.depth_code(0.25f), 2));
  EXPECT_EQ(b.slot(slot_of(1, 0)), l.pack(2, l.depth_code(0.75f), 1));  // h_2((0,0)) = (1,0)
  std::vector<ListEntry> list;
  b.list(0, 0, list);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].data, 2u);
  EXPECT_EQ(list[1].data, 1u);
  EXPECT_EQ(b.max_age().at(0, 0), 2u);
}

TEST(Insert, OlderRecordEvictsYoungerRecordOfAnotherPixel) {
  HaBuffer b = traced_buffer();
  const RecordLayout& l = b.record_layout();
  b.insert_one({1, 0, 0.5f, 7});   // pixel (1,0) at age 1 in slot (1,0)
  b.insert_one({0, 0, 0.1f, 8});   // pixel (0,0) age 1 in slot (0,0)
  b.insert_one({0, 0, 0.2f, 9});   // age 2 for (0,0) probes (1,0): age 2 > 1 evicts pixel (1,0)'s record
  EXPECT_EQ(b.slot(slot_of(1, 0)), l.pack(2, l.depth_code(0.2f), 9));
  EXPECT_EQ(b.slot(slot_of(2, 0)), l.pack(2, l.depth_code(0.5f), 7));  // (1,0) + O[1] = (2,0)
  std::vector<ListEntry> list;
  b.list(1, 0, list);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].age, 2u);
  EXPECT_EQ(list[0].data, 7u);
}

TEST(Insert, IdenticalFragmentIsCountedDuplicateAndStoredOnce) {
  HaBuffer b = traced_buffer();
  const std::vector<Fragment> f{{2, 2, 0.3f, 5}, {2, 2, 0.3f, 5}, {2, 2, 0.3f, 6}};
  const Counters c = b.insert(f);
  EXPECT_EQ(c.duplicates, 1u);
  EXPECT_EQ(c.stored(), 2u);
  std::vector<ListEntry> list;
  b.list(2, 2, list);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].data, 6u) << "equal depth: larger data first";
}

TEST(Insert, L32IgnoresDataSoEqualDepthsAreDuplicates) {
  BufferConfig c = test::config({4, 4}, {4, 4}, Layout::L32, 4);
  HaBuffer b = test::make_buffer(c);
  const Counters n = b.insert(std::vector<Fragment>{{1, 1, 0.3f, 5}, {1, 1, 0.3f, 6}});
  EXPECT_EQ(n.duplicates, 1u);
  EXPECT_EQ(b.count_stored(), 1u);
}

TEST(Insert, InvalidDepthsAreCountedNotStored) {
  HaBuffer b = traced_buffer();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Counters c = b.insert(std::vector<Fragment>{{0, 0, nan, 1}, {0, 0, -0.5f, 1}, {0, 0, 1.5f, 1},
                                                    {0, 0, std::numeric_limits<float>::infinity(), 1}, {0, 0, 1.0f, 1}});
  EXPECT_EQ(c.invalid, 4u);
  EXPECT_EQ(c.stored(), 1u);
  EXPECT_EQ(b.count_stored(), 1u);
}

TEST(Insert, AgeOverflowDropsTheFarthestRecordsAndCountsThemWithoutHanging) {
  // Age bits 4: AMAX = 15. Twenty distinct fragments on one pixel of a big table.
  BufferConfig c = test::config({1, 1}, {64, 64}, Layout::L64, 4);
  HaBuffer b = test::make_buffer(c);
  std::vector<Fragment> f;
  for (int i = 0; i < 20; ++i) f.push_back({0, 0, static_cast<float>(i) / 20.0f, static_cast<std::uint32_t>(i)});
  const Counters n = b.insert(test::shuffled(f, 3));
  EXPECT_EQ(n.failed_age, 5u);
  EXPECT_EQ(n.stored(), 15u);
  EXPECT_EQ(b.count_stored(), 15u);
  std::vector<ListEntry> list;
  b.list(0, 0, list);
  ASSERT_EQ(list.size(), 15u);
  for (std::uint32_t i = 0; i < 15; ++i) EXPECT_EQ(list[i].data, i) << "the 15 nearest survive, in order";
}

TEST(Insert, IterationLimitFailsTheCallAndIsCounted) {
  HaBuffer b = traced_buffer(/*iter_limit=*/1);
  EXPECT_EQ(b.insert_one({0, 0, 0.5f, 1}), HABUFFER_STORED);
  // Needs two probes (age 1 taken by a nearer record, then age 2): over the limit.
  EXPECT_EQ(b.insert_one({0, 0, 0.9f, 1}), HABUFFER_FAILED_ITER);
  EXPECT_EQ(b.count_stored(), 1u);
}

TEST(Insert, EvictedRecordMayBeTheOneLostAndTheCountersSayAFragmentWasLost) {
  // AMAX = 15 and 16 fragments: the last call evicts and the evicted record fails.
  BufferConfig c = test::config({1, 1}, {64, 64}, Layout::L64, 4);
  HaBuffer b = test::make_buffer(c);
  Counters n;
  for (int i = 15; i >= 0; --i)  // farthest first: each new one is nearer and pushes all others down
    n.count(b.insert_one({0, 0, static_cast<float>(i) / 16.0f, 0}));
  EXPECT_EQ(n.failed_age, 1u);
  EXPECT_EQ(n.stored(), 15u);
  EXPECT_EQ(b.count_stored(), 15u);
  std::vector<ListEntry> list;
  b.list(0, 0, list);
  EXPECT_EQ(list.front().code, b.record_layout().depth_code(0.0f)) << "the nearest (inserted last) is kept";
}

TEST(Insert, MaxAgeTableCellsCoverBlocksOfPixels) {
  HaBuffer b = traced_buffer(HABUFFER_DEFAULT_ITER_LIMIT, /*block=*/3);
  EXPECT_EQ(b.max_age().cells(), (Extent{2, 2}));
  b.insert(std::vector<Fragment>{{3, 3, 0.1f, 0}, {3, 3, 0.2f, 0}, {3, 3, 0.3f, 0}});
  EXPECT_EQ(b.max_age().at(1, 1), 3u);
  EXPECT_EQ(b.max_age().at(0, 0), 0u);
}

TEST(Insert, OffScreenPixelIsRejectedBeforeAnythingIsInserted) {
  HaBuffer b = traced_buffer();
  try {
    b.insert(std::vector<Fragment>{{0, 0, 0.5f, 1}, {4, 0, 0.5f, 1}});
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("fragment 1 at pixel (4,0)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(b.count_stored(), 0u);
}

TEST(Insert, ClearReturnsTheStoredCountAndEmptiesBothTables) {
  HaBuffer b = traced_buffer();
  b.insert(std::vector<Fragment>{{0, 0, 0.5f, 1}, {1, 1, 0.5f, 1}, {1, 1, 0.6f, 1}});
  EXPECT_EQ(b.clear(), 3u);
  EXPECT_EQ(b.count_stored(), 0u);
  EXPECT_EQ(b.max_age().max(), 0u);
}

// SPEC 7's early stop, counted: the walk of a pixel reads slots for ages
// 1, 2, ... and stops at the first slot holding a younger record (or the
// cell's max age), never reading on to the max age of its 8x8 block when it
// can stop. Removing the stop would leave the lists unchanged (Proposition A)
// but not the reads.
TEST(Traverse, TheWalkStopsAtTheFirstYoungerRecordNotAtTheCellsMaxAge) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const BufferConfig c = test::config({24, 24}, {40, 40}, Layout::L64, 8, 8);
    HaBuffer b = test::make_buffer(c, seed);
    b.insert(test::stream(c.screen, StreamKind::Coherent, 1000, seed));
    const RecordLayout& l = b.record_layout();
    std::uint64_t early = 0;
    std::vector<ListEntry> list;
    for (std::uint32_t y = 0; y < c.screen.y; ++y)
      for (std::uint32_t x = 0; x < c.screen.x; ++x) {
        const std::uint32_t amax = b.max_age().at(x / c.block, y / c.block);
        std::uint32_t expected = amax;
        for (std::uint32_t a = 1; a <= amax; ++a) {
          const glm::uvec2 o = b.offsets()[a - 1];
          const std::uint64_t s = (x + o.x) % c.table.x + std::uint64_t{(y + o.y) % c.table.y} * c.table.x;
          if (l.age(b.slot(s)) < a) {
            expected = a;
            break;
          }
        }
        ASSERT_EQ(b.list(x, y, list), expected) << "pixel " << x << "," << y;
        early += expected < amax;
      }
    EXPECT_GT(early, 100u) << "most walks end before their cell's max age";
  }
}

TEST(Traverse, EachVisitStepEmitsSkipsOrStops) {
  const RecordLayout l(Layout::L64, 8);
  const std::uint64_t age3 = l.pack(3, 100, 7);
  using Kernel = HashKernel<std::uint64_t, false>;
  KernelParams params;
  Kernel k(params, nullptr, nullptr, nullptr);
  EXPECT_EQ(k.ha_visit(age3, 3), HABUFFER_VISIT_EMIT);
  EXPECT_EQ(k.ha_visit(age3, 2), HABUFFER_VISIT_SKIP) << "an older record of another pixel: walk on";
  EXPECT_EQ(k.ha_visit(age3, 4), HABUFFER_VISIT_STOP) << "a younger record: nothing of this pixel lies beyond";
  EXPECT_EQ(k.ha_visit(0, 1), HABUFFER_VISIT_STOP) << "an empty slot";
}

TEST(Config, TableSmallerThanScreenIsRejectedNamingBothSizes) {
  BufferConfig c = test::config({640, 480}, {640, 479});
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("640x479"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos);
  }
}

TEST(Config, OffsetsMustMatchTheTableAndAges) {
  BufferConfig c = test::config({4, 4}, {8, 8});
  EXPECT_THROW(HaBuffer(c, OffsetSequence::random({9, 8}, 255, 1)), std::invalid_argument);
  EXPECT_THROW(HaBuffer(c, OffsetSequence::random({8, 8}, 15, 1)), std::invalid_argument);
  c.early_cull_tau = 0.5f;
  c.layout = Layout::L32;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
