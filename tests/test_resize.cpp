// SPEC 8: resize policy and lossless mode.
#include <gtest/gtest.h>

#include "habuffer/lossless_build.h"
#include "test_support.h"

namespace habuffer {
namespace {

TEST(ResizePolicy, GrowsAboveEightyShrinksBelowThirtyKeepsOtherwise) {
  const ResizePolicy p;
  const Extent screen{1000, 500}, table{2000, 1000};
  EXPECT_EQ(p.next(table, screen, 1'700'000), p.grown(table));   // 0.85
  EXPECT_EQ(p.next(table, screen, 500'000), p.shrunk(table, screen));  // 0.25
  EXPECT_EQ(p.next(table, screen, 1'000'000), table);             // 0.5
  EXPECT_EQ(p.next(table, screen, 1'600'000), table);             // exactly 0.8 keeps
}

TEST(ResizePolicy, StepsScaleTheAreaByAQuarterKeepingTheAspectRatio) {
  const ResizePolicy p;
  const Extent g = p.grown({2000, 1000});
  EXPECT_EQ(g, (Extent{2237, 1119}));  // ceil(2000 * sqrt(1.25)), ceil(1000 * sqrt(1.25))
  EXPECT_NEAR(static_cast<double>(g.area()) / 2e6, 1.25, 0.002);
  const Extent s = p.shrunk({2000, 1000}, {10, 10});
  EXPECT_EQ(s, (Extent{1733, 867}));  // ceil(2000 * sqrt(0.75)), ceil(1000 * sqrt(0.75))
}

TEST(ResizePolicy, NeverShrinksBelowTheScreenAndAlwaysGrows) {
  const ResizePolicy p;
  EXPECT_EQ(p.shrunk({1100, 600}, {1024, 512}), (Extent{1024, 520}));
  EXPECT_EQ(p.next({1024, 512}, {1024, 512}, 0), (Extent{1024, 512}));
  EXPECT_GT(p.grown({1, 1}).area(), 1u);
}

TEST(ResizePolicy, ThresholdsAreConfigurableAndValidated) {
  ResizePolicy p{0.9, 0.1, 0.5};
  EXPECT_NO_THROW(p.validate());
  EXPECT_EQ(p.next({100, 100}, {10, 10}, 8500), (Extent{100, 100}));
  EXPECT_THROW((ResizePolicy{0.3, 0.8, 0.25}.validate()), std::invalid_argument);
  EXPECT_THROW((ResizePolicy{0.8, 0.3, 1.5}.validate()), std::invalid_argument);
}

// A scripted sequence of frames whose content grows then shrinks: the table
// follows SPEC 8 frame by frame (CPU counts are exact, so no latency here).
TEST(ResizePolicy, FollowsGrowingThenShrinkingContent) {
  const ResizePolicy p;
  const Extent screen{256, 256};
  Extent table = screen;
  std::vector<Extent> sizes;
  for (double load_of_screen : {0.5, 0.9, 1.2, 1.5, 1.5, 1.5, 0.3, 0.1, 0.1, 0.1, 0.1}) {
    const auto stored = static_cast<std::uint64_t>(load_of_screen * static_cast<double>(screen.area()));
    const Extent before = table;
    table = p.next(table, screen, stored);
    // The decision of every frame follows from the load it measured.
    const double load = static_cast<double>(stored) / static_cast<double>(before.area());
    SCOPED_TRACE("load " + std::to_string(load) + " in " + before.str());
    if (load > p.grow_at) {
      EXPECT_EQ(table, p.grown(before));
      EXPECT_GE(static_cast<double>(table.area()), 1.25 * static_cast<double>(before.area()));
    } else if (load < p.shrink_at && before != screen) {
      EXPECT_LT(table.area(), before.area());
      EXPECT_GE(static_cast<double>(table.area()), 0.75 * static_cast<double>(before.area()));
    } else {
      EXPECT_EQ(table, before);
    }
    sizes.push_back(table);
    EXPECT_GE(table.x, screen.x);
    EXPECT_GE(table.y, screen.y);
  }
  EXPECT_EQ(sizes[0], screen);
  EXPECT_GT(sizes[1].area(), screen.area());
  EXPECT_EQ(sizes.back(), screen) << "shrinks back to the screen, never below";
}

TEST(Lossless, GrowsAndRegathersUntilNothingFails) {
  const Extent screen{64, 64};
  const auto f = test::stream(screen, StreamKind::Random, 64 * 64 * 3 / 2, 4);  // load 1.5 on the screen-sized table
  BufferConfig c = test::config(screen, screen, Layout::L64, 6);
  const BuildResult once = build(c, OffsetSource{}, f, {});
  EXPECT_GT(once.counters.failures(), 0u);
  const BuildResult r = build(c, OffsetSource{}, f, {}, ResizePolicy{}, 20);
  EXPECT_TRUE(r.lossless());
  EXPECT_GT(r.attempts.size(), 1u);
  EXPECT_GT(r.buffer.table().area(), screen.area());
  for (std::size_t i = 1; i < r.attempts.size(); ++i) EXPECT_GT(r.attempts[i].table.area(), r.attempts[i - 1].table.area());
  EXPECT_EQ(test::traversed_lists(r.buffer), test::exact_lists(f, r.buffer.record_layout()));
}

TEST(Lossless, ReportsFailureWhenAPixelIsDeeperThanAmaxAfterBoundedAttempts) {
  std::vector<Fragment> f;
  for (int i = 0; i < 20; ++i) f.push_back({0, 0, static_cast<float>(i) / 20.0f, 0});
  BufferConfig c = test::config({2, 2}, {2, 2}, Layout::L64, 4);
  const BuildResult r = build(c, OffsetSource{}, f, {}, ResizePolicy{}, 5);
  EXPECT_FALSE(r.lossless());
  EXPECT_EQ(r.attempts.size(), 5u);
  EXPECT_EQ(r.counters.failed_age, 5u);
}

TEST(Lossless, KeepsAGivenOffsetListValidForLargerTables) {
  OffsetSource src;
  src.generator = OffsetGenerator::List;
  for (std::uint32_t i = 0; i < 15; ++i) src.list.emplace_back(i % 4, i / 4);
  const auto f = test::stream({4, 4}, StreamKind::Random, 40, 1);
  const BuildResult r = build(test::config({4, 4}, {4, 4}, Layout::L64, 4), src, f, {}, ResizePolicy{}, 30);
  EXPECT_TRUE(r.lossless());
  EXPECT_EQ(r.buffer.offsets()[5], (glm::uvec2{1, 1}));
}

}  // namespace
}  // namespace habuffer
