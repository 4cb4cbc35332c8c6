// SPEC 8: resize policy and lossless mode.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "habuffer/data_error.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique_frames.h"
#include "habuffer/pixel_depth.h"
#include "test_support.h"

namespace habuffer {
namespace {

// The paper's step rule (ResizeRule::Step), kept for studies.
const ResizePolicy kStep{0.80, 0.30, 0.25, ResizeRule::Step};

TEST(ResizePolicy, GrowsAboveEightyShrinksBelowThirtyKeepsOtherwise) {
  const ResizePolicy p = kStep;
  const Extent screen{1000, 500}, table{2000, 1000};
  EXPECT_EQ(p.next(table, screen, 1'700'000), p.grown(table));   // 0.85
  EXPECT_EQ(p.next(table, screen, 500'000), p.shrunk(table, screen));  // 0.25
  EXPECT_EQ(p.next(table, screen, 1'000'000), table);             // 0.5
  EXPECT_EQ(p.next(table, screen, 1'600'000), table);             // exactly 0.8 keeps
}

TEST(ResizePolicy, StepsScaleTheAreaByAQuarterKeepingTheAspectRatio) {
  const ResizePolicy p = kStep;
  const Extent g = p.grown({2000, 1000});
  EXPECT_EQ(g, (Extent{2237, 1119}));  // ceil(2000 * sqrt(1.25)), ceil(1000 * sqrt(1.25))
  EXPECT_NEAR(static_cast<double>(g.area()) / 2e6, 1.25, 0.002);
  const Extent s = p.shrunk({2000, 1000}, {10, 10});
  EXPECT_EQ(s, (Extent{1733, 867}));  // ceil(2000 * sqrt(0.75)), ceil(1000 * sqrt(0.75))
}

TEST(ResizePolicy, NeverShrinksBelowTheScreenAndAlwaysGrows) {
  const ResizePolicy p = kStep;
  EXPECT_EQ(p.shrunk({1100, 600}, {1024, 512}), (Extent{1024, 520}));
  EXPECT_EQ(p.next({1024, 512}, {1024, 512}, 0), (Extent{1024, 512}));
  EXPECT_GT(p.grown({1, 1}).area(), 1u);
}

TEST(ResizePolicy, ThresholdsAreConfigurableAndValidated) {
  ResizePolicy p{0.9, 0.1, 0.5, ResizeRule::Step};
  EXPECT_NO_THROW(p.validate());
  EXPECT_EQ(p.next({100, 100}, {10, 10}, 8500), (Extent{100, 100}));
  EXPECT_THROW((ResizePolicy{0.3, 0.8, 0.25}.validate()), std::invalid_argument);
  EXPECT_THROW((ResizePolicy{0.8, 0.3, 1.5}.validate()), std::invalid_argument);
}

// A scripted sequence of frames whose content grows then shrinks: the table
// follows SPEC 8 frame by frame (CPU counts are exact, so no latency here).
TEST(ResizePolicy, TheStepRuleFollowsGrowingThenShrinkingContentOneStepPerDecision) {
  const ResizePolicy p = kStep;
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

// The count rule (the default): a decision leaves the band straight to the
// counted records at the middle of the band, whatever the jump.
TEST(ResizePolicy, TheCountRuleSizesForTheCountedRecordsAtTheMiddleOfTheBandInOneDecision) {
  const ResizePolicy p;
  EXPECT_EQ(p.rule, ResizeRule::Count);
  EXPECT_DOUBLE_EQ(p.target_load(), 0.55);
  const Extent screen{64, 64};
  for (std::uint64_t records : {163'840ull, 40'960ull, 5'000ull, 3'300ull}) {
    SCOPED_TRACE(records);
    const Extent t = p.next(screen, screen, records);  // from the screen, load records / 4096
    const double load = static_cast<double>(records) / static_cast<double>(t.area());
    EXPECT_GE(load, p.target_load() * 0.98);
    EXPECT_LE(load, p.target_load()) << "rounded up: never above the middle";
    EXPECT_EQ(t, p.initial_table(screen, records)) << "the same table the counting pass gives";
  }
  // Inside the band: kept, at both edges included.
  const Extent t{100, 100};
  EXPECT_EQ(p.next(t, screen, 8000), t);
  EXPECT_EQ(p.next(t, screen, 3000), t);
  EXPECT_EQ(p.next(t, screen, 5500), t);
  // A drop: straight back to the middle of the band (or the screen) in one decision.
  const Extent big = p.initial_table(screen, 163'840);
  const Extent after_drop = p.next(big, screen, 4096);  // 40 layers to 1
  EXPECT_EQ(after_drop, p.initial_table(screen, 4096));
  EXPECT_EQ(p.next(big, screen, 10), screen) << "never below the screen";
  EXPECT_EQ(p.next(screen, screen, 0), screen);
  // Pools: the same rule in records.
  EXPECT_EQ(p.next(1000, 900), p.counted_capacity(900));
  EXPECT_EQ(p.next(1000, 100), p.counted_capacity(100));
  EXPECT_EQ(p.next(1000, 500), 1000u);
  EXPECT_EQ(p.counted_capacity(550), 1000u);
  EXPECT_EQ(p.counted_capacity(0), 1u);
}

TEST(ResizePolicy, LosslessGrowthHoldsTheCountInOneStepAndAlwaysGrows) {
  const ResizePolicy p;
  const Extent screen{32, 32};
  const Extent g = p.grown(screen, screen, 40'960);  // an empty frame's table, then 40 layers
  EXPECT_EQ(g, p.initial_table(screen, 40'960));
  EXPECT_LE(40'960.0 / static_cast<double>(g.area()), p.target_load());
  // A failure at a load inside the band (an unlucky pixel) still grows, by a step.
  const Extent t{100, 100};
  EXPECT_EQ(p.grown(t, screen, 5000), p.grown(t));
  EXPECT_GT(p.grown(t, screen, 0).area(), t.area());
  EXPECT_EQ(kStep.grown(t, screen, 1'000'000), kStep.grown(t)) << "the step rule ignores the count";
  // Pools.
  EXPECT_EQ(p.grown(100, 5000), p.counted_capacity(5000));
  EXPECT_EQ(p.grown(100, 10), 101u);
  EXPECT_EQ(kStep.grown(100, 5000), 5000u);
  EXPECT_EQ(kStep.grown(100, 10), 125u);
}

TEST(ResizePolicy, ACountBeyondTwoToTheThirtyTwoSlotsIsCappedNotThrown) {
  const ResizePolicy p;
  const Extent screen{4096, 4096};
  const Extent t = p.next(screen, screen, 4'000'000'000ull);
  EXPECT_LE(t.area(), std::uint64_t{UINT32_MAX});
  EXPECT_GT(t.area(), screen.area());
  EXPECT_GE(t.x, screen.x);
  EXPECT_LE(p.grown(screen, screen, 4'000'000'000ull).area(), std::uint64_t{UINT32_MAX});
}

// A load oscillating 5 % around either threshold: the count rule lands mid
// band on the first crossing, and resizes no more (the hysteresis).
TEST(ResizePolicy, ALoadOscillatingAroundEitherThresholdResizesAtMostOnce) {
  const ResizePolicy p;
  const Extent screen{128, 128};
  for (const double threshold : {p.grow_at, p.shrink_at}) {
    for (const ResizePolicy& rule : {p, kStep}) {
      if (rule.rule == ResizeRule::Step && threshold == p.shrink_at) continue;  // a step from 0.3 stays outside 0.3
      SCOPED_TRACE(std::string(to_string(rule.rule)) + " around " + std::to_string(threshold));
      Extent table{400, 400};
      const double base = threshold * static_cast<double>(table.area());
      int resizes = 0;
      for (int k = 0; k < 200; ++k) {
        const double wobble = (k % 2 == 0 ? 1.05 : 0.95) * (1.0 + 0.001 * std::sin(k));
        const Extent next = rule.next(table, screen, static_cast<std::uint64_t>(base * wobble));
        resizes += next != table;
        table = next;
      }
      EXPECT_LE(resizes, 1);
    }
  }
}

TEST(ResizePolicy, RulesAreSpelledCountAndStep) {
  EXPECT_EQ(parse_resize_rule("count"), ResizeRule::Count);
  EXPECT_EQ(parse_resize_rule("step"), ResizeRule::Step);
  EXPECT_EQ(to_string(ResizeRule::Step), "step");
  try {
    (void)parse_resize_rule("half");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "resize rule 'half': expected count or step");
  }
}

// The jumps of a host whose depth complexity leaps in one frame, on the CPU
// path's kept frames (as render's and Python's): lossless in at most two
// attempts, the regather sized by the failed attempt's own count.
TEST(Lossless, AnyJumpIsLosslessInAtMostOneRegatherSizedByTheFailedAttemptsCount) {
  const Extent screen{32, 32};
  const ResizePolicy policy;
  for (const int from : {0, 1}) {
    SCOPED_TRACE("jump " + std::to_string(from) + " -> 40 layers");
    TechniqueConfig c = ha_technique_config(test::config(screen, {}, Layout::L64, 8));
    c.buffer.table = policy.initial_table(screen, std::max<std::uint64_t>(1, from * screen.area()));
    TechniqueFrames frames(OffsetSource{}, InsertOptions{}, policy, 16);
    (void)frames.build(c, layered_stream(screen, from, 1));
    const std::vector<Fragment> deep = layered_stream(screen, 40, 2);
    const TechniqueBuild& b = frames.build(c, deep);
    EXPECT_TRUE(b.lossless());
    ASSERT_EQ(b.attempts.size(), 2u);
    EXPECT_GT(b.attempts[0].counters.failures(), 0u);
    EXPECT_EQ(b.attempts[0].sized_for, 0u);
    EXPECT_EQ(b.attempts[1].sized_for, 40u * screen.area()) << "every fragment received, counted";
    EXPECT_EQ(b.attempts[1].table, policy.grown(b.attempts[0].table, screen, 40u * screen.area()));
    EXPECT_GE(b.attempts[1].ms, 0.0);
    EXPECT_EQ(test::traversed_lists(*b.buffer), test::exact_lists(deep, c.buffer.record_layout()));
    // The step rule takes many attempts for the same jump.
    TechniqueFrames stepped(OffsetSource{}, InsertOptions{}, kStep, 6);
    (void)stepped.build(c, layered_stream(screen, from, 1));
    EXPECT_FALSE(stepped.build(c, deep).lossless()) << "six steps of a quarter do not reach 40 layers";
  }
}

TEST(Lossless, APoolJumpIsLosslessInOneRegatherToo) {
  const Extent screen{16, 16};
  TechniqueConfig c = ha_technique_config(test::config(screen, {}, Layout::L64, 8));
  c.technique = Technique::Lists;
  c.pool_capacity = 64;
  const std::vector<Fragment> deep = layered_stream(screen, 40, 3);
  const TechniqueBuild b = build_technique(c, OffsetSource{}, deep, {}, ResizePolicy{}, 16);
  EXPECT_TRUE(b.lossless());
  ASSERT_EQ(b.attempts.size(), 2u);
  EXPECT_EQ(b.attempts[1].sized_for, deep.size());
  EXPECT_EQ(b.attempts[1].capacity, ResizePolicy{}.counted_capacity(deep.size()));
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

TEST(Lossless, StopsAtOnceNamingThePixelWhenItIsDeeperThanAmaxAtAnyTableSize) {
  std::vector<Fragment> f;
  for (int i = 0; i < 20; ++i) f.push_back({1, 0, static_cast<float>(i) / 20.0f, 0});
  BufferConfig c = test::config({2, 2}, {2, 2}, Layout::L64, 4);
  const BuildResult r = build(c, OffsetSource{}, f, {}, ResizePolicy{}, 5);
  EXPECT_FALSE(r.lossless());
  EXPECT_EQ(r.attempts.size(), 1u) << "growing cannot hold 20 records at one pixel with AMAX 15";
  EXPECT_EQ(r.counters.failed_age, 16u) << "the first table's 4 slots";
  ASSERT_TRUE(r.too_deep.has_value());
  EXPECT_EQ(r.too_deep->pixel, glm::uvec2(1, 0));
  EXPECT_EQ(r.too_deep->records, 20u);
  EXPECT_NE(too_deep_message(*r.too_deep, 4).find("use --age-bits 5"), std::string::npos);
}

TEST(Lossless, StillGrowsWhenADeepPixelsFragmentsAreDuplicatesWithinAmax) {
  // 30 fragments at one pixel but 10 distinct records: AMAX 15 holds them,
  // so a table too small for the other pixels' records must still grow.
  std::vector<Fragment> f;
  for (int i = 0; i < 30; ++i) f.push_back({0, 0, static_cast<float>(i % 10) / 10.0f, 7});
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 4; ++x)
      for (int k = 0; k < 3; ++k) f.push_back({x, y, 0.05f + 0.3f * static_cast<float>(k), 1});
  BufferConfig c = test::config({4, 4}, {4, 4}, Layout::L64, 4);
  const BuildResult r = build(c, OffsetSource{}, f, {}, ResizePolicy{}, 20);
  EXPECT_FALSE(r.too_deep.has_value());
  EXPECT_TRUE(r.lossless());
  EXPECT_GT(r.attempts.size(), 1u);
}

// `n` distinct depths at pixel (x, y), one colour.
std::vector<Fragment> one_deep_pixel(std::uint32_t x, std::uint32_t y, int n) {
  std::vector<Fragment> f;
  for (int i = 0; i < n; ++i) f.push_back({x, y, (static_cast<float>(i) + 0.5f) / static_cast<float>(n), 7});
  return f;
}

// The message of require_lossless, or "" when it did not throw.
std::string lossless_error(const TechniqueBuild& b, std::span<const Fragment> f, std::uint32_t max_attempts,
                           OptionSpelling spelling = OptionSpelling::Flag) {
  try {
    require_lossless(b, f, max_attempts, spelling);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

TEST(Lossless, TheRuleOfEveryPathGrowsUnlessAPixelIsDeeperThanAnyTableHolds) {
  const std::vector<Fragment> f = one_deep_pixel(1, 0, 20);
  const TechniqueConfig a4 = ha_technique_config(test::config({2, 2}, {2, 2}, Layout::L64, 4));
  const AttemptLimit deep = lossless_attempts(a4, f, 5);
  EXPECT_EQ(deep.attempts, 1u) << "20 records at one pixel, AMAX 15: no table holds them";
  ASSERT_TRUE(deep.too_deep.has_value());
  EXPECT_EQ(deep.too_deep->pixel, glm::uvec2(1, 0));
  EXPECT_EQ(deep.too_deep->records, 20u);
  const AttemptLimit one = lossless_attempts(a4, f, 1);
  EXPECT_EQ(one.attempts, 1u);
  EXPECT_FALSE(one.too_deep.has_value()) << "one attempt asks nothing of the stream";
  const AttemptLimit a5 = lossless_attempts(ha_technique_config(test::config({2, 2}, {2, 2}, Layout::L64, 5)), f, 5);
  EXPECT_EQ(a5.attempts, 5u) << "AMAX 31 holds them: growth may help";
  EXPECT_FALSE(a5.too_deep.has_value());
  TechniqueConfig culled = a4;
  culled.buffer.early_cull_tau = 0.5f;
  EXPECT_EQ(lossless_attempts(culled, f, 5).attempts, 5u) << "early cull may cull them";
  TechniqueConfig lists = a4;
  lists.technique = Technique::Lists;
  EXPECT_EQ(lossless_attempts(lists, f, 5).attempts, 5u) << "no AMAX limits the lists";
}

// The rule's boundary (issue 46, part 8): AMAX + 1 distinct records at a
// pixel are beyond every table, AMAX are not (an off-by-one would let
// lossless mode grow uselessly, or refuse a pixel a table holds).
TEST(Lossless, APixelOfAmaxPlusOneRecordsIsBeyondEveryTableAndOneOfAmaxIsNot) {
  for (const std::uint32_t age_bits : {4u, 6u}) {
    const RecordLayout layout(Layout::L64, age_bits);
    const int amax = static_cast<int>(layout.max_age());
    SCOPED_TRACE("AMAX " + std::to_string(amax));
    const TechniqueConfig c = ha_technique_config(test::config({2, 2}, {2, 2}, Layout::L64, age_bits));
    const AttemptLimit beyond = lossless_attempts(c, one_deep_pixel(1, 1, amax + 1), 8);
    EXPECT_EQ(beyond.attempts, 1u);
    ASSERT_TRUE(beyond.too_deep.has_value());
    EXPECT_EQ(beyond.too_deep->records, static_cast<std::uint64_t>(amax + 1));
    const AttemptLimit within = lossless_attempts(c, one_deep_pixel(1, 1, amax), 8);
    EXPECT_EQ(within.attempts, 8u);
    EXPECT_FALSE(within.too_deep.has_value());
    // And a build of AMAX records at one pixel does end lossless by growing.
    const TechniqueBuild b = build_technique(c, OffsetSource{}, one_deep_pixel(1, 1, amax), {}, ResizePolicy{}, 8);
    EXPECT_TRUE(b.lossless());
  }
}

// An automatic pool's guaranteed second attempt (issue 46, part 8): paged
// lists take whole pages, so a pool sized for the fragments at grow_at use
// drops; the automatic pool is gathered again at once even with one attempt
// asked for, and holds every fragment.
TEST(Lossless, AnAutomaticPoolIsGatheredAgainAtOnceEvenWithOneAttempt) {
  const Extent screen{16, 16};
  std::vector<Fragment> f;  // one fragment a pixel: a page a fragment
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) f.push_back({x, y, 0.5f, 7});
  TechniqueConfig c = test::technique_config(Technique::PagedLists, screen, Layout::L64, 8);
  c.pool_capacity = 0;  // automatic
  const TechniqueBuild b = build_technique(c, OffsetSource{}, f, {}, ResizePolicy{}, 1);
  ASSERT_EQ(b.attempts.size(), 2u);
  EXPECT_GT(b.attempts[0].counters.dropped_pool, 0u);
  EXPECT_EQ(b.attempts[0].capacity, ResizePolicy{}.automatic(f.size()));
  EXPECT_TRUE(b.lossless());
  EXPECT_EQ(b.counters.stored(), f.size());
}

TEST(Lossless, ALossyEndWhereGrowingCannotHelpThrowsADataErrorNamingThePixelAgeBitsAndMaxAttempts) {
  const std::vector<Fragment> f = one_deep_pixel(1, 0, 20);
  const TechniqueBuild b =
      build_technique(ha_technique_config(test::config({2, 2}, {2, 2}, Layout::L64, 4)), OffsetSource{}, f, {},
                      ResizePolicy{}, 5);
  ASSERT_EQ(b.attempts.size(), 1u);
  const std::string flag = lossless_error(b, f, 5);
  EXPECT_EQ(flag.rfind("lossless mode: 16 of 20 fragments not stored: ", 0), 0u) << flag;  // the 2x2 table's 4 slots
  EXPECT_NE(flag.find(" after 1 attempt: pixel (1, 0) has 20 distinct fragments, more than AMAX = 2^4 - 1 = 15"),
            std::string::npos)
      << flag;
  EXPECT_NE(flag.find("use --age-bits 5"), std::string::npos) << flag;
  EXPECT_NE(flag.find("more attempts cannot help (--max-attempts 5)"), std::string::npos) << flag;
  EXPECT_EQ(flag.find('\n'), std::string::npos) << "one line";
  const std::string keyword = lossless_error(b, f, 5, OptionSpelling::Keyword);
  EXPECT_NE(keyword.find("use age_bits=5"), std::string::npos) << keyword;
  EXPECT_NE(keyword.find("(max_attempts=5)"), std::string::npos) << keyword;
}

TEST(Lossless, ALossyEndAfterEveryAttemptThrowsADataErrorNamingThePixelAmaxTheAttemptsAndMaxAttempts) {
  // 4000 records at one pixel fit AMAX 4095, so the build grows, but two
  // attempts from a 4x4 table cannot hold them.
  const std::vector<Fragment> f = one_deep_pixel(1, 2, 4000);
  const TechniqueBuild b =
      build_technique(ha_technique_config(test::config({4, 4}, {4, 4}, Layout::L64, 12)), OffsetSource{}, f, {},
                      kStep, 2);  // two steps from 16 slots cannot hold 4000 records
  ASSERT_FALSE(b.lossless());
  EXPECT_EQ(b.attempts.size(), 2u);
  EXPECT_FALSE(b.too_deep.has_value());
  const std::string m = lossless_error(b, f, 2);
  EXPECT_NE(m.find(" after 2 attempts (last table "), std::string::npos) << m;
  EXPECT_NE(m.find("; AMAX = 2^12 - 1 = 4095): pixel (1, 2) lost the most, "), std::string::npos) << m;
  EXPECT_NE(m.find(" of its 4000 distinct records: raise --max-attempts above 2"), std::string::npos) << m;
  EXPECT_EQ(m.find("age-bits"), std::string::npos) << "growing may help: " << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
  EXPECT_NE(lossless_error(b, f, 2, OptionSpelling::Keyword).find("raise max_attempts above 2"), std::string::npos);
  const TechniqueBuild whole =
      build_technique(ha_technique_config(test::config({4, 4}, {4, 4}, Layout::L64, 12)), OffsetSource{},
                      one_deep_pixel(1, 2, 10), {}, ResizePolicy{}, 2);
  ASSERT_TRUE(whole.lossless());
  EXPECT_NO_THROW(require_lossless(whole, one_deep_pixel(1, 2, 10), 2));
  EXPECT_EQ(lossless_failure_reason(whole, one_deep_pixel(1, 2, 10), 2), "");
}

TEST(Lossless, NamesThePixelThatLostTheMostWithoutAmaxForTechniquesWithoutATable) {
  std::vector<Fragment> f = one_deep_pixel(2, 1, 5);
  f.push_back({0, 0, 0.5f, 1});
  f.push_back({0, 0, 0.25f, 1});  // K = 2 holds this pixel's
  TechniqueConfig c;
  c.technique = Technique::Arrays;
  c.layers = 2;
  c.buffer = test::config({4, 4}, {}, Layout::L64, 8);
  const TechniqueBuild b = build_technique(c, OffsetSource{}, f, {});
  ASSERT_EQ(b.counters.failures(), 3u);
  const std::optional<PixelLoss> p = pixel_most_lost(*b.buffer, f);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->pixel, glm::uvec2(2, 1));
  EXPECT_EQ(p->records, 5u);
  EXPECT_EQ(p->lost, 3u);
  const std::string m = lossless_failure_reason(b, f, 1);
  EXPECT_NE(m.find("pixel (2, 1) lost the most, 3 of its 5 distinct records: raise --max-attempts above 1"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("AMAX"), std::string::npos) << m;
}

TEST(PixelDepth, CountsDistinctRecordsSkippingInvalidAndOffScreenFragments) {
  const RecordLayout l64(Layout::L64, 4), l32(Layout::L32, 4);
  std::vector<Fragment> f;
  for (int i = 0; i < 16; ++i) f.push_back({2, 1, 0.5f, static_cast<std::uint32_t>(i)});  // one depth, 16 colours
  f.push_back({2, 1, std::nanf(""), 99});
  f.push_back({2, 1, 1.5f, 98});
  for (int i = 0; i < 40; ++i) f.push_back({9, 9, static_cast<float>(i) / 40.0f, 0});  // off a 4x4 screen
  const std::optional<PixelDepth> d64 = pixel_deeper_than(f, {4, 4}, l64, 15);
  ASSERT_TRUE(d64.has_value());
  EXPECT_EQ(d64->pixel, glm::uvec2(2, 1));
  EXPECT_EQ(d64->records, 16u);
  EXPECT_FALSE(pixel_deeper_than(f, {4, 4}, l64, 16).has_value()) << "exactly the limit is not beyond it";
  EXPECT_FALSE(pixel_deeper_than(f, {4, 4}, l32, 1).has_value()) << "L32 records carry no data: one record";
}

TEST(PixelDepth, NamesTheAgeBitsThatHoldAPixelOrSaysNoneDo) {
  EXPECT_EQ(age_bits_for(15), std::optional<std::uint32_t>(4));
  EXPECT_EQ(age_bits_for(16), std::optional<std::uint32_t>(5));
  EXPECT_EQ(age_bits_for(4095), std::optional<std::uint32_t>(12));
  EXPECT_FALSE(age_bits_for(4096).has_value());
  EXPECT_NE(too_deep_message({{0, 0}, 5000, false}, 8).find("fragments (duplicates included)"), std::string::npos);
  EXPECT_NE(too_deep_message({{0, 0}, 5000, true}, 8).find("another technique"), std::string::npos);
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
