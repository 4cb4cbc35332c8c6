// Extremes: sizes, loads and index arithmetic at their limits.
#include <gtest/gtest.h>

#include "habuffer/hash_kernel.h"
#include "test_support.h"

namespace habuffer {
namespace {

TEST(Extremes, TableExactlyTheScreenAtLoadNearOneAccountsForEverything) {
  for (Layout layout : {Layout::L64, Layout::L32}) {
    const Extent screen{96, 80};
    const BufferConfig c = test::config(screen, screen, layout, 8);
    HaBuffer b = test::make_buffer(c, 3);
    const auto f = test::stream(screen, StreamKind::Random, screen.area() * 99 / 100, 8);
    const Counters n = b.insert(f);
    EXPECT_EQ(b.count_stored(), n.stored());
    EXPECT_GT(static_cast<double>(n.stored()) / static_cast<double>(screen.area()), 0.97);
    if (n.failures() == 0) {
      EXPECT_EQ(test::traversed_lists(b), test::exact_lists(f, b.record_layout()));
    }
  }
}

TEST(Extremes, FullTableWithMoreFragmentsThanSlotsFailsCountedNeverHangs) {
  const Extent screen{16, 16};
  const BufferConfig c = test::config(screen, screen, Layout::L64, 4);
  HaBuffer b = test::make_buffer(c, 1);
  const auto f = test::stream(screen, StreamKind::Random, 600, 2);  // 2.3 per slot
  const Counters n = b.insert(f);
  EXPECT_GT(n.failed_age, 0u);
  EXPECT_EQ(b.count_stored(), n.stored());
  EXPECT_LE(n.stored(), screen.area());
}

TEST(Extremes, OnePixelScreenAndOneSlotTable) {
  const BufferConfig c = test::config({1, 1}, {1, 1}, Layout::L64, 4);
  HaBuffer b = test::make_buffer(c, 1);  // a single offset, repeated cyclically for all 15 ages
  const Counters n = b.insert(std::vector<Fragment>{{0, 0, 0.5f, 1}, {0, 0, 0.25f, 2}, {0, 0, 0.75f, 3}});
  EXPECT_EQ(n.stored(), 1u);
  EXPECT_EQ(n.failed_age, 2u);
  std::vector<ListEntry> list;
  b.list(0, 0, list);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].data, 2u) << "the nearest record keeps the only slot";
}

TEST(Extremes, TablesSmallerThanAmaxUseCyclicOffsetsAndStayCorrect) {
  const Extent screen{3, 2};
  const BufferConfig c = test::config(screen, {4, 3}, Layout::L64, 8);  // 12 slots, AMAX 255
  HaBuffer b = test::make_buffer(c, 5);
  const auto f = test::stream(screen, StreamKind::Random, 10, 1);
  const Counters n = b.insert(f);
  EXPECT_EQ(b.count_stored(), n.stored());
  if (n.failures() == 0) {
    EXPECT_EQ(test::traversed_lists(b), test::exact_lists(f, b.record_layout()));
  }
}

TEST(Extremes, AgeBitsTwelveAndDepthBitsTwentyAtTheirLimits) {
  const Extent screen{8, 8};
  const BufferConfig c = test::config(screen, {64, 64}, Layout::L64, 12);
  HaBuffer b = test::make_buffer(c, 2);
  std::vector<Fragment> f;
  for (std::uint32_t i = 0; i < 300; ++i) f.push_back({3, 4, static_cast<float>(i) / 300.0f, i});  // depth 300 > 255
  f.push_back({0, 0, 1.0f, 7});   // code 0
  f.push_back({0, 0, 0.0f, 7});   // code 2^20 - 1
  const Counters n = b.insert(f);
  EXPECT_EQ(n.failures(), 0u);
  std::vector<ListEntry> list;
  b.list(3, 4, list);
  EXPECT_EQ(list.size(), 300u);
  b.list(0, 0, list);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].code, (1u << 20) - 1);
  EXPECT_EQ(list[1].code, 0u);
}

// Slot indices are 64-bit: a 65600 x 65600 table has 4.3e9 slots. The kernel's
// index arithmetic is checked directly, then a real L32 buffer of that size
// (17 GB of address space, only touched pages committed) stores and finds
// records beyond slot 2^32.
TEST(Extremes, SlotIndicesBeyondTwoToTheThirtyTwo) {
  KernelParams p;
  p.table = {65600, 65600};
  p.max_age_cells_x = 8200;
  const glm::uvec2 offsets[1] = {{65599, 65599}};
  HashKernel<std::uint32_t, false> k(p, offsets, nullptr, nullptr);
  EXPECT_EQ(k.ha_slot(glm::uvec2(65599, 65599)), 65599ull + 65599ull * 65600ull);
  EXPECT_GT(k.ha_slot(glm::uvec2(65599, 65599)), 0xFFFFFFFFull);
  EXPECT_EQ(k.ha_probe(glm::uvec2(65599, 65599), 1), glm::uvec2(65598, 65598));  // wraps on both axes
  EXPECT_EQ(k.ha_owner(glm::uvec2(65598, 65598), 1), glm::uvec2(65599, 65599));

  BufferConfig c = test::config({1000, 1000}, {65600, 65600}, Layout::L32, 4, 8);
  std::vector<glm::uvec2> rows;
  for (std::uint32_t i = 0; i < 15; ++i) rows.emplace_back(64600 + i, 65000 + i);
  HaBuffer b(c, OffsetSequence::from_list(c.table, 15, rows));
  const std::vector<Fragment> f{{999, 500, 0.5f, 0}, {999, 500, 0.25f, 0}, {998, 500, 0.5f, 0}};
  const Counters n = b.insert(f);
  EXPECT_EQ(n.stored(), 3u);
  std::vector<ListEntry> list;
  b.list(999, 500, list);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].code, b.record_layout().depth_code(0.25f));
  EXPECT_EQ(list[1].code, b.record_layout().depth_code(0.5f));
  // Pixel (999, 500) at age 1: slot ((999 + 64600) mod 65600, 500 + 65000) = (65599, 65500).
  const std::uint64_t s = 65599 + 65500ull * 65600;
  EXPECT_GT(s, 0xFFFFFFFFull);
  EXPECT_EQ(b.record_layout().age(b.slot(s)), 1u);
  EXPECT_EQ(b.record_layout().code(b.slot(s)), b.record_layout().depth_code(0.25f));
}

}  // namespace
}  // namespace habuffer
