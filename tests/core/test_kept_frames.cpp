// Containers kept across frames (issue 26, habuffer/technique_frames.h):
// a frame on a kept container gives exactly what a fresh container gives,
// whatever the frame before it held, for every technique.
#include <gtest/gtest.h>

#include "habuffer/technique_frames.h"
#include "test_support.h"

namespace habuffer {
namespace {

// Frames of different content: a full one, one on other pixels (smaller),
// an empty one, and the first again.
std::vector<std::vector<Fragment>> varied_frames(Extent screen) {
  std::vector<std::vector<Fragment>> frames;
  frames.push_back(test::stream(screen, StreamKind::Coherent, 2400, 5));
  std::vector<Fragment> right_half;
  for (const Fragment& f : test::stream(screen, StreamKind::Random, 900, 6))
    if (f.x >= screen.x / 2) right_half.push_back(f);
  frames.push_back(right_half);
  frames.push_back({});
  frames.push_back(frames.front());
  return frames;
}

TechniqueConfig config_of(Technique t, Extent screen) {
  TechniqueConfig c = test::technique_config(t, screen);
  c.buffer.table = {screen.x * 2, screen.y * 2};  // load under 0.5: nothing fails, so threads cannot tell
  c.pool_capacity = 4000;
  c.layers = 16;
  return c;
}

TEST(KeptFrames, EveryTechniqueGivesWhatAFreshContainerGivesFrameAfterFrame) {
  const Extent screen{40, 30};
  const auto frames = varied_frames(screen);
  for (Technique t : all_techniques()) {
    SCOPED_TRACE(to_string(t));
    const TechniqueConfig c = config_of(t, screen);
    for (std::uint32_t threads : {1u, 2u}) {
      InsertOptions o;
      o.threads = threads;
      TechniqueFrames kept(OffsetSource{}, o);
      for (std::size_t k = 0; k < frames.size(); ++k) {
        SCOPED_TRACE("frame " + std::to_string(k) + " threads " + std::to_string(threads));
        const TechniqueBuild& b = kept.build(c, frames[k]);
        const TechniqueBuild fresh = build_technique(c, OffsetSource{}, frames[k], o);
        EXPECT_EQ(b.counters, fresh.counters);
        EXPECT_EQ(b.buffer->count_stored(), fresh.buffer->count_stored());
        if (stores_lists(t)) {
          EXPECT_EQ(test::traversed_lists(*b.buffer), test::traversed_lists(*fresh.buffer));
        }
        const std::vector<glm::vec3> bg(screen.area(), glm::vec3(0.25f, 0.5f, 1.0f));
        EXPECT_TRUE(test::same_bits(b.buffer->composite_image(bg, 1), fresh.buffer->composite_image(bg, 1)));
      }
      EXPECT_EQ(kept.containers_made(), 1u) << "one configuration: one container for every frame";
    }
  }
}

TEST(KeptFrames, TheHaBufferKeepsItsTableAndMaxAgeTableBitForBit) {
  const Extent screen{40, 30};
  const auto frames = varied_frames(screen);
  const TechniqueConfig c = config_of(Technique::Ha, screen);
  TechniqueFrames kept(OffsetSource{}, InsertOptions{});
  for (const auto& frame : frames) {
    const auto& held = static_cast<const HaBuffer&>(*kept.build(c, frame).buffer);
    const TechniqueBuild fresh = build_technique(c, OffsetSource{}, frame, InsertOptions{});
    const auto& ha = static_cast<const HaBuffer&>(*fresh.buffer);
    EXPECT_EQ(test::table_words(held), test::table_words(ha));
    EXPECT_EQ(held.max_age().ages(), ha.max_age().ages());
  }
}

// A table resized between frames (SPEC 8's next size, as render's adaptive
// frames choose it) is a new container; returning to a size makes one again.
TEST(KeptFrames, AnotherSizeMakesANewContainerAndItsFramesMatchFreshOnes) {
  const Extent screen{40, 30};
  const auto frames = varied_frames(screen);
  TechniqueConfig c = config_of(Technique::Ha, screen);
  TechniqueFrames kept(OffsetSource{}, InsertOptions{});
  const ResizePolicy policy;
  std::uint64_t expected_made = 0;
  Extent previous{};
  for (const auto& frame : frames) {
    const TechniqueBuild& b = kept.build(c, frame);
    if (c.buffer.table != previous) ++expected_made;
    previous = c.buffer.table;
    const TechniqueBuild fresh = build_technique(c, OffsetSource{}, frame, InsertOptions{});
    EXPECT_EQ(test::traversed_lists(*b.buffer), test::traversed_lists(*fresh.buffer));
    EXPECT_EQ(kept.containers_made(), expected_made);
    c.buffer.table = policy.next(c.buffer.table, screen, b.counters.stored());
  }
  EXPECT_GT(expected_made, 1u) << "the frames must resize the table";
}

// Lossless mode in a kept container: a frame that overflows grows to a new
// container, and its result is the fresh lossless build's.
TEST(KeptFrames, ALosslessRegrowthInsideAFrameMatchesAFreshLosslessBuild) {
  const Extent screen{30, 20};
  const std::vector<Fragment> small = test::stream(screen, StreamKind::Coherent, 300, 12);
  const std::vector<Fragment> large = test::stream(screen, StreamKind::Coherent, 4000, 12);
  for (Technique t : {Technique::Ha, Technique::Lists, Technique::Arrays}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = 400;
    c.layers = 2;
    c.buffer.table = {60, 40};  // 2400 slots: the small frame fits, the large one (4000) does not
    TechniqueFrames kept(OffsetSource{}, InsertOptions{}, ResizePolicy{}, 8);
    kept.build(c, small);
    const TechniqueBuild& b = kept.build(c, large);
    const TechniqueBuild fresh = build_technique(c, OffsetSource{}, large, InsertOptions{}, ResizePolicy{}, 8);
    EXPECT_TRUE(b.lossless());
    EXPECT_GT(b.attempts.size(), 1u);
    EXPECT_EQ(b.attempts.size(), fresh.attempts.size());
    EXPECT_EQ(b.counters, fresh.counters);
    EXPECT_EQ(test::traversed_lists(*b.buffer), test::traversed_lists(*fresh.buffer));
  }
}

TEST(KeptFrames, LastAndReleaseRefuseBeforeTheFirstFrame) {
  TechniqueFrames frames(OffsetSource{}, InsertOptions{});
  EXPECT_THROW((void)frames.last(), std::logic_error);
  EXPECT_THROW((void)frames.release(), std::logic_error);
  EXPECT_THROW(TechniqueFrames(OffsetSource{}, InsertOptions{}, ResizePolicy{}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
