// Linked lists and fixed arrays on the GPU path: the same lists as their CPU
// builds and as the HA-buffer on the same captured stream, every drop
// counted, lossless regathering, the sort pass beyond the private array, and
// the resolve's image bit for bit the HA-buffer's.
#include <gtest/gtest.h>

#include <algorithm>

#include "gl_test_support.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/gl/techniques/arrays/gl_fixed_arrays.h"
#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer {
namespace {

using test::ExactLists;

TechniqueConfig technique_config(Technique t, Extent screen, gl::AtomicMode mode, std::uint32_t age_bits = 8) {
  return test::technique_config(t, screen, test::layout_of(mode), age_bits);
}

std::unique_ptr<gl::GlTechnique> gl_technique(const TechniqueConfig& c, gl::AtomicMode mode,
                                              const gl::GlBindings& bindings = {}) {
  return gl::make_gl_technique(c, OffsetSource{}, mode, bindings);
}

class GlTechniques : public ::testing::Test {
 protected:
  void SetUp() override { test::gl_context(); }
  static std::vector<gl::AtomicMode> modes() { return {gl::AtomicMode::Native32, gl::AtomicMode::Emulated64}; }
};

// Each technique declares the passes its frame needs beyond the gather, and
// only those: the HA-buffer its clear pass at the frame's start, the
// techniques that sort after the gather a sort pass (and those sorted while
// inserting none, as their descriptors say), the k-buffer its fill and count
// pass only with occupancy culling, the blended baselines the framebuffer
// their gather draws into.
TEST_F(GlTechniques, EachTechniqueDeclaresThePassesItsFrameNeeds) {
  using gl::GlPassStage;
  const auto stages = [](const gl::GlTechnique& t) {
    std::vector<GlPassStage> out;
    for (const gl::GlPass& p : t.passes()) {
      out.push_back(p.stage);
      EXPECT_FALSE(p.name.empty());
      EXPECT_TRUE(p.run);
      EXPECT_EQ(p.framebuffer != 0, p.stage == GlPassStage::Gather) << p.name;
    }
    return out;
  };
  for (const TechniqueDescriptor* d : technique_registry()) {
    SCOPED_TRACE(std::string(d->name));
    TechniqueConfig c = technique_config(d->technique, {8, 8}, gl::AtomicMode::Native32);
    const auto t = gl_technique(c, gl::AtomicMode::Native32);
    std::vector<GlPassStage> expected;
    if (d->capacity == CapacityKind::TableSlots) expected = {GlPassStage::FrameStart};
    else if (d->capacity == CapacityKind::None) expected = {GlPassStage::Gather};
    else if (!d->sorted_on_insert) expected = {GlPassStage::Sort};
    EXPECT_EQ(stages(*t), expected);
    EXPECT_EQ(t->gather_framebuffer() != 0, d->capacity == CapacityKind::None);
  }
  TechniqueConfig occupancy = technique_config(Technique::KBuffer, {8, 8}, gl::AtomicMode::Native32);
  occupancy.occupancy = true;
  EXPECT_EQ(stages(*gl_technique(occupancy, gl::AtomicMode::Native32)), std::vector<GlPassStage>{GlPassStage::Fill});
}

TEST_F(GlTechniques, ListsAndArraysOnTheGpuGiveTheCpuAndHaBufferListsOverSeedsAndLayouts) {
  for (gl::AtomicMode mode : modes())
    for (Technique t : {Technique::Lists, Technique::Arrays})
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const Extent screen{13 + 7 * static_cast<std::uint32_t>(seed), 9 + 2 * static_cast<std::uint32_t>(seed)};
        const StreamKind kind = seed == 2 ? StreamKind::Hot : StreamKind::Coherent;
        const std::uint32_t age_bits = seed == 3 ? 5 : 8;
        const std::vector<Fragment> frags = test::stream(screen, kind, 900 + seed * 300, seed);
        TechniqueConfig c = technique_config(t, screen, mode, age_bits);
        c.pool_capacity = frags.size();
        c.layers = test::depth_complexity(frags, screen);
        gl::GlFrameDriver gpu(gl_technique(c, mode));
        gl::ComputeInserter inserter(gpu);
        const gl::FrameReport report = inserter.insert(frags);
        const auto cpu = make_fragment_buffer(c, OffsetSource{});
        const Counters expected = cpu->insert(frags);
        EXPECT_EQ(report.counters, expected) << to_string(t) << " " << to_string(mode) << " seed " << seed;
        const ExactLists gl_lists = test::traversed_lists(*gpu.technique().read_back());
        EXPECT_EQ(gl_lists, test::traversed_lists(*cpu)) << to_string(t) << " " << to_string(mode) << " seed " << seed;
        const BuildResult ha = build(c.buffer, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
        EXPECT_EQ(gl_lists, test::traversed_lists(ha.buffer));
        EXPECT_EQ(report.counters, ha.counters);
      }
}

TEST_F(GlTechniques, AFullPoolIsCountedAndLosslessModeRegathersIntoAPoolThatHoldsEveryFragment) {
  const Extent screen{24, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 3000, 4);
  for (gl::AtomicMode mode : modes()) {
    TechniqueConfig c = technique_config(Technique::Lists, screen, mode);
    c.pool_capacity = 1000;
    gl::GlFrameDriver lossy(gl_technique(c, mode));
    const gl::FrameReport r = gl::ComputeInserter(lossy).insert(frags);
    EXPECT_EQ(r.counters.dropped_pool, frags.size() - 1000) << to_string(mode);
    EXPECT_EQ(r.nodes_requested, frags.size());
    EXPECT_EQ(r.counters.stored(), lossy.technique().read_back()->count_stored());

    gl::GlFrameOptions options;
    options.max_attempts = 4;
    gl::GlFrameDriver lossless(gl_technique(c, mode), options);
    const gl::FrameReport l = gl::ComputeInserter(lossless).insert(frags);
    EXPECT_TRUE(l.lossless()) << to_string(mode);
    ASSERT_EQ(l.attempts.size(), 2u);
    EXPECT_EQ(l.attempts[0].capacity, 1000u);
    EXPECT_GE(l.capacity, frags.size());
    const BuildResult ha = build(c.buffer, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
    EXPECT_EQ(test::traversed_lists(*lossless.technique().read_back()), test::traversed_lists(ha.buffer));
  }
}

TEST_F(GlTechniques, ArraysWithFewLayersCountTheSameDropsAsTheCpuKeepListsSortedAndGrowWhenLossless) {
  const Extent screen{20, 12};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 2000, 6);
  for (gl::AtomicMode mode : modes()) {
    TechniqueConfig c = technique_config(Technique::Arrays, screen, mode);
    c.layers = 4;
    gl::GlFrameDriver gpu(gl_technique(c, mode));
    const gl::FrameReport r = gl::ComputeInserter(gpu).insert(frags);
    FixedArrays cpu(c);
    const Counters expected = cpu.insert(frags);
    // Which K fragments a pixel keeps depends on arrival order; how many does not.
    EXPECT_EQ(r.counters.dropped_layers, expected.dropped_layers) << to_string(mode);
    EXPECT_EQ(r.most_arrived, cpu.largest_overflow());
    const auto back = gpu.technique().read_back();
    std::vector<ListEntry> list;
    std::uint64_t held = 0;
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x) {
        back->list(x, y, list);
        held += list.size();
        EXPECT_LE(list.size(), 4u);
        for (std::size_t k = 1; k < list.size(); ++k)
          EXPECT_TRUE(list[k - 1].code > list[k].code || (list[k - 1].code == list[k].code && list[k - 1].data > list[k].data));
      }
    EXPECT_EQ(held, r.counters.stored());

    gl::GlFrameOptions options;
    options.max_attempts = 3;
    gl::GlFrameDriver lossless(gl_technique(c, mode), options);
    const gl::FrameReport l = gl::ComputeInserter(lossless).insert(frags);
    EXPECT_TRUE(l.lossless()) << to_string(mode);
    EXPECT_EQ(l.capacity, std::uint64_t{test::depth_complexity(frags, screen)} * screen.area());
  }
}

TEST_F(GlTechniques, ListsLongerThanThePrivateArrayAreSortedOnTheGpu) {
  const Extent screen{4, 4};
  std::vector<Fragment> frags;
  SplitMix64 rng(3);
  for (int i = 0; i < 300; ++i)
    frags.push_back({2, 1, static_cast<float>(rng.below(200)) / 211.0f, 0x40506000u + static_cast<std::uint32_t>(rng.below(2))});
  for (Technique t : {Technique::Lists, Technique::Arrays}) {
    TechniqueConfig c = technique_config(t, screen, gl::AtomicMode::Emulated64);
    c.pool_capacity = frags.size();
    c.layers = static_cast<std::uint32_t>(frags.size());
    gl::GlFrameDriver gpu(gl_technique(c, gl::AtomicMode::Emulated64));
    const gl::FrameReport r = gl::ComputeInserter(gpu).insert(frags);
    const ExactLists expected = test::exact_lists(frags, RecordLayout(Layout::L64, 8));
    ASSERT_GT(expected.at({2, 1}).size(), HABUFFER_SORT_LOCAL);
    EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), expected) << to_string(t);
    EXPECT_EQ(r.counters.duplicates, frags.size() - expected.at({2, 1}).size()) << to_string(t);
  }
}

TEST_F(GlTechniques, ExactTechniquesResolveTheHaBuffersImageBitForBitAtHostBindings) {
  const Extent screen{32, 24};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 5000, 8);
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  BufferConfig hc = test::config(screen, Extent{40, 30}, Layout::L64);
  gl::GlFrameOptions lossless;
  lossless.max_attempts = 8;
  gl::GlHaBuffer ha(hc, test::random_offsets(2), mode, lossless, test::host_bindings());
  ASSERT_TRUE(gl::ComputeInserter(ha).insert(frags).lossless());
  const glm::vec3 background(0.2f, 0.4f, 0.9f);
  const std::vector<glm::vec4> expected = test::resolve_to_image(ha, background);
  for (Technique t : {Technique::Lists, Technique::Arrays}) {
    TechniqueConfig c = technique_config(t, screen, mode);
    c.pool_capacity = frags.size();
    c.layers = test::depth_complexity(frags, screen);
    gl::GlFrameDriver gpu(gl_technique(c, mode, test::host_bindings()));
    gl::ComputeInserter(gpu).insert(frags);
    EXPECT_EQ(test::resolve_to_image(gpu, background), expected) << to_string(t);
  }
}

TEST_F(GlTechniques, AdaptivePoolGrowsPastItsGrowThresholdAndShrinksBelowItsShrinkThreshold) {
  const Extent screen{16, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Random, 900, 2);
  TechniqueConfig c = technique_config(Technique::Lists, screen, gl::AtomicMode::Emulated64);
  c.pool_capacity = 1000;  // 90% use: grows to the middle of the band next frame (the count rule)
  gl::GlFrameOptions options;
  options.adaptive = true;
  gl::GlFrameDriver gpu(gl_technique(c, gl::AtomicMode::Emulated64), options);
  gl::ComputeInserter inserter(gpu);
  EXPECT_EQ(inserter.insert(frags).capacity, 1000u);
  const gl::FrameReport grown = inserter.insert(frags);
  EXPECT_TRUE(grown.resized);
  EXPECT_EQ(grown.capacity, ResizePolicy{}.counted_capacity(900));  // 1637: 900 at 55 % use
  const std::span<const Fragment> few(frags.data(), 100);  // 6% use: shrinks to the middle of the band
  inserter.insert(few);
  const gl::FrameReport shrunk = inserter.insert(few);
  EXPECT_TRUE(shrunk.resized);
  EXPECT_EQ(shrunk.capacity, ResizePolicy{}.counted_capacity(100));  // 182
  EXPECT_EQ(shrunk.counters.stored(), 100u);
}

// The GPU containers refuse what the CPU ones refuse (issue 25): sizes with a
// zero side, before anything divides by them, and another technique's
// configuration.
TEST_F(GlTechniques, GpuContainersRefuseZeroSidesAndAnotherTechniquesConfiguration) {
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  const auto refused = [](auto&& f, const std::string& part) {
    try {
      f();
      ADD_FAILURE() << "nothing thrown; expected " << part;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  for (const Extent zero : {Extent{0, 5}, Extent{5, 0}, Extent{0, 0}}) {
    refused([&] { gl::GlHaBuffer b(test::config(zero, {}), test::random_offsets(1), mode); }, "screen size " + zero.str());
    for (Technique t : all_techniques()) {
      TechniqueConfig c = technique_config(t, zero, mode);
      c.pool_capacity = 10;
      refused([&] { (void)gl_technique(c, mode); }, "screen size " + zero.str());
    }
  }
  refused([&] { gl::GlHaBuffer b(test::config({8, 8}, {1000, 0}), test::random_offsets(1), mode); }, "table 1000x0");
  gl::GlHaBuffer ok(test::config({8, 8}, {}), test::random_offsets(1), mode);
  refused([&] { ok.resize({0, 1000}); }, "table 0x1000");
  TechniqueConfig lists = technique_config(Technique::Lists, {8, 8}, mode);
  lists.pool_capacity = 10;
  refused([&] { gl::GlFixedArrays a(lists, mode, {}); }, "technique arrays's container refuses a configuration of technique lists");
  TechniqueConfig arrays = technique_config(Technique::Arrays, {8, 8}, mode);
  refused([&] { gl::GlLinkedLists l(arrays, mode, {}); }, "technique lists's container refuses a configuration of technique arrays");
}

}  // namespace
}  // namespace habuffer
