// The techniques behind one interface (FragmentBuffer): linked lists and
// fixed arrays give the HA-buffer's lists byte for byte when nothing is
// dropped, count every drop (SPEC invariant 1 for every technique), and
// composite the same image.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"
#include "test_support.h"

namespace habuffer {
namespace {

using test::ExactLists;

BuildResult lossless_ha(const BufferConfig& c, const std::vector<Fragment>& frags) {
  BuildResult r = build(c, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
  EXPECT_TRUE(r.lossless());
  return r;
}

struct StreamCase {
  StreamKind kind;
  Layout layout;
  std::uint32_t age_bits;
};

class ExactTechniques : public ::testing::TestWithParam<StreamCase> {};

TEST_P(ExactTechniques, ListsAndArraysGiveTheHaBuffersListsByteForByteOverSeeds) {
  const StreamCase p = GetParam();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Extent screen{17 + static_cast<std::uint32_t>(seed) * 3, 11 + static_cast<std::uint32_t>(seed)};
    const std::vector<Fragment> frags = test::stream(screen, p.kind, 400 + seed * 150, seed);
    const BuildResult ha = lossless_ha(test::config(screen, screen, p.layout, p.age_bits), frags);
    const ExactLists expected = test::traversed_lists(ha.buffer);
    ASSERT_EQ(expected, test::exact_lists(frags, ha.buffer.record_layout())) << "seed " << seed;

    TechniqueConfig lc = test::technique_config(Technique::Lists, screen, p.layout, p.age_bits);
    lc.pool_capacity = frags.size();
    LinkedLists lists(lc);
    const Counters cl = lists.insert(frags);
    EXPECT_EQ(test::traversed_lists(lists), expected) << "lists, seed " << seed;
    EXPECT_EQ(cl.failures(), 0u);
    EXPECT_EQ(cl.stored(), lists.count_stored());

    TechniqueConfig ac = test::technique_config(Technique::Arrays, screen, p.layout, p.age_bits);
    ac.layers = test::depth_complexity(frags, screen);
    FixedArrays arrays(ac);
    const Counters ca = arrays.insert(frags);
    EXPECT_EQ(test::traversed_lists(arrays), expected) << "arrays, seed " << seed;
    EXPECT_EQ(ca.failures(), 0u);
    EXPECT_EQ(ca.stored(), arrays.count_stored());

    // Every outcome agrees with the HA-buffer's: duplicates merged and counted the same.
    EXPECT_EQ(cl, ha.counters) << "seed " << seed;
    EXPECT_EQ(ca, ha.counters) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(Streams, ExactTechniques,
                         ::testing::Values(StreamCase{StreamKind::Coherent, Layout::L64, 8},
                                           StreamCase{StreamKind::Random, Layout::L64, 5},
                                           StreamCase{StreamKind::Hot, Layout::L64, 8},
                                           StreamCase{StreamKind::Coherent, Layout::L32, 8},
                                           StreamCase{StreamKind::Hot, Layout::L32, 12}));

TEST(Techniques, ListsLongerThanThePrivateArrayAreSortedInPlaceAndMerged) {
  // One pixel receives hundreds of fragments, many identical: the merge sort
  // (lists) and heap sort (arrays) paths, beyond HABUFFER_SORT_LOCAL entries.
  const Extent screen{3, 2};
  std::vector<Fragment> frags;
  SplitMix64 rng(7);
  for (int i = 0; i < 700; ++i)
    frags.push_back({1, 1, static_cast<float>(rng.below(90)) / 97.0f, 0x10203000u + static_cast<std::uint32_t>(rng.below(3))});
  frags.push_back({0, 0, 0.5f, 0x11223344u});
  const ExactLists expected = test::exact_lists(frags, RecordLayout(Layout::L64, 8));
  ASSERT_GT(expected.at({1, 1}).size(), HABUFFER_SORT_LOCAL);
  TechniqueConfig lc = test::technique_config(Technique::Lists, screen);
  lc.pool_capacity = frags.size();
  LinkedLists lists(lc);
  const Counters cl = lists.insert(frags);
  EXPECT_EQ(test::traversed_lists(lists), expected);
  EXPECT_EQ(cl.duplicates, frags.size() - 1 - expected.at({1, 1}).size());
  TechniqueConfig ac = test::technique_config(Technique::Arrays, screen);
  ac.layers = 700;
  FixedArrays arrays(ac);
  const Counters ca = arrays.insert(frags);
  EXPECT_EQ(test::traversed_lists(arrays), expected);
  EXPECT_EQ(ca, cl);
}

TEST(Techniques, ParallelInsertionBuildsTheSameListsAsOneThread) {
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 20000, 3);
  for (Technique t : {Technique::Lists, Technique::Arrays}) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = frags.size();
    c.layers = test::depth_complexity(frags, screen);
    const std::unique_ptr<FragmentBuffer> serial = make_fragment_buffer(c, OffsetSource{});
    const std::unique_ptr<FragmentBuffer> parallel = make_fragment_buffer(c, OffsetSource{});
    const Counters a = serial->insert(frags);
    InsertOptions options;
    options.threads = 4;
    options.mode = InsertMode::Atomic;
    const Counters b = parallel->insert(frags, options);
    EXPECT_EQ(a, b) << to_string(t);
    EXPECT_EQ(test::traversed_lists(*serial), test::traversed_lists(*parallel)) << to_string(t);
  }
}

TEST(Techniques, ArraysWithFewLayersKeepTheFirstKOfEachPixelSortedAndCountTheRest) {
  const Extent screen{20, 14};
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 1500, seed);
    const std::uint32_t k = 3;
    TechniqueConfig c = test::technique_config(Technique::Arrays, screen);
    c.layers = k;
    FixedArrays arrays(c);
    const Counters counters = arrays.insert(frags);
    // Serial insertion keeps the first K arrivals of every pixel.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> arrived;
    std::vector<Fragment> kept;
    std::uint64_t dropped = 0;
    for (const Fragment& f : frags) {
      if (arrived[{f.x, f.y}]++ < k) kept.push_back(f);
      else ++dropped;
    }
    EXPECT_EQ(counters.dropped_layers, dropped);
    EXPECT_EQ(test::traversed_lists(arrays), test::exact_lists(kept, RecordLayout(Layout::L64, 8))) << "seed " << seed;
    EXPECT_EQ(counters.stored(), arrays.count_stored());
    std::uint32_t most = 0;
    for (const auto& [p, n] : arrived) most = std::max(most, n);
    EXPECT_EQ(arrays.largest_overflow(), most);
  }
}

TEST(Techniques, AFullPoolDropsAndCountsEveryFragmentBeyondIt) {
  const Extent screen{16, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Random, 900, 5);
  TechniqueConfig c = test::technique_config(Technique::Lists, screen);
  c.pool_capacity = 500;
  LinkedLists lists(c);
  const Counters counters = lists.insert(frags);
  EXPECT_EQ(counters.dropped_pool, frags.size() - 500);
  EXPECT_EQ(lists.requested(), frags.size());
  EXPECT_EQ(counters.stored(), lists.count_stored());
  const std::vector<Fragment> first(frags.begin(), frags.begin() + 500);
  EXPECT_EQ(test::traversed_lists(lists), test::exact_lists(first, RecordLayout(Layout::L64, 8)));
}

TEST(Techniques, TwoBatchesEqualOneAndClearEmptiesEverything) {
  const Extent screen{24, 24};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 3000, 9);
  const std::span<const Fragment> all(frags);
  for (Technique t : {Technique::Lists, Technique::Arrays}) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = frags.size();
    c.layers = test::depth_complexity(frags, screen);
    const std::unique_ptr<FragmentBuffer> one = make_fragment_buffer(c, OffsetSource{});
    const std::unique_ptr<FragmentBuffer> two = make_fragment_buffer(c, OffsetSource{});
    const Counters whole = one->insert(all);
    Counters halves = two->insert(all.first(1234));
    halves += two->insert(all.subspan(1234));
    EXPECT_EQ(whole, halves) << to_string(t);
    EXPECT_EQ(test::traversed_lists(*one), test::traversed_lists(*two)) << to_string(t);
    EXPECT_EQ(two->clear(), whole.stored());
    EXPECT_EQ(two->count_stored(), 0u);
    EXPECT_TRUE(test::traversed_lists(*two).empty());
  }
}

TEST(Techniques, ExactTechniquesCompositeTheHaBuffersImageBitForBit) {
  const Extent screen{40, 30};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 8000, 11);
  const HaBuffer ha = std::move(lossless_ha(test::config(screen, screen), frags).buffer);
  std::vector<glm::vec3> backgrounds(screen.area());
  for (std::size_t i = 0; i < backgrounds.size(); ++i) backgrounds[i] = glm::vec3(float(i % 7) / 7.0f, 0.25f, 1.0f);
  const std::vector<glm::vec4> expected = ha.composite_image(backgrounds, 2);
  TechniqueConfig lc = test::technique_config(Technique::Lists, screen);
  lc.pool_capacity = frags.size();
  LinkedLists lists(lc);
  lists.insert(frags);
  EXPECT_EQ(lists.composite_image(backgrounds, 2), expected);
  TechniqueConfig ac = test::technique_config(Technique::Arrays, screen);
  ac.layers = test::depth_complexity(frags, screen);
  FixedArrays arrays(ac);
  arrays.insert(frags);
  EXPECT_EQ(arrays.composite_image(backgrounds, 2), expected);
}

TEST(Techniques, InvalidDepthsAndOffScreenFragmentsAreRefusedOrCountedNeverStored) {
  const Extent screen{4, 4};
  const std::vector<Fragment> frags{{0, 0, -0.5f, 1}, {1, 1, 2.0f, 1}, {2, 2, std::nanf(""), 1}, {3, 3, 0.25f, 7}};
  TechniqueConfig c = test::technique_config(Technique::Lists, screen);
  c.pool_capacity = 8;
  LinkedLists lists(c);
  const Counters counters = lists.insert(frags);
  EXPECT_EQ(counters.invalid, 3u);
  EXPECT_EQ(counters.stored(), 1u);
  const std::vector<Fragment> off{{4, 0, 0.5f, 1}};
  EXPECT_THROW(lists.insert(off), std::out_of_range);
  TechniqueConfig a = test::technique_config(Technique::Arrays, screen);
  FixedArrays arrays(a);
  EXPECT_EQ(arrays.insert(frags).invalid, 3u);
  EXPECT_THROW(arrays.insert(off), std::out_of_range);
}

TEST(Techniques, BadConfigurationsAreRefusedNamingTheField) {
  TechniqueConfig c = test::technique_config(Technique::Lists, {8, 8});
  c.pool_capacity = 0;
  EXPECT_THROW(LinkedLists{c}, std::invalid_argument);
  c.pool_capacity = 10;
  c.buffer.early_cull_tau = 0.5f;
  EXPECT_THROW(LinkedLists{c}, std::invalid_argument);
  TechniqueConfig a = test::technique_config(Technique::Arrays, {8, 8});
  a.layers = 0;
  EXPECT_THROW(FixedArrays{a}, std::invalid_argument);
  a.layers = 1u << 28;
  EXPECT_THROW(FixedArrays{a}, std::invalid_argument);
  InsertOptions owner;
  owner.mode = InsertMode::OwnerComputes;
  a.layers = 4;
  FixedArrays arrays(a);
  EXPECT_THROW(arrays.insert({}, owner), std::invalid_argument);
  EXPECT_EQ(parse_technique("lists"), Technique::Lists);
  EXPECT_FALSE(parse_technique("list").has_value());
}

TEST(Techniques, LosslessBuildsGrowThePoolAndTheLayersUntilNothingIsDropped) {
  const Extent screen{30, 20};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 4000, 12);
  const ExactLists expected = test::exact_lists(frags, RecordLayout(Layout::L64, 8));
  for (Technique t : {Technique::Lists, Technique::Arrays}) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = 100;
    c.layers = 2;
    const TechniqueBuild lossy = build_technique(c, OffsetSource{}, frags, InsertOptions{});
    EXPECT_GT(lossy.counters.failures(), 0u) << to_string(t);
    const TechniqueBuild b = build_technique(c, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 4);
    EXPECT_TRUE(b.lossless()) << to_string(t);
    EXPECT_EQ(b.attempts.size(), 2u) << to_string(t);
    EXPECT_EQ(test::traversed_lists(*b.buffer), expected) << to_string(t);
  }
}

// pool_capacity 0 is the automatic pool, as the CLI's --pool auto: a build
// sizes it for its fragments at grow_at use and loses nothing in one
// attempt; a container made without fragments still refuses it, saying who takes it.
TEST(Techniques, AnAutomaticPoolIsSizedFromTheFragmentsAndHoldsThemInOneAttempt) {
  const Extent screen{30, 20};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 4000, 12);
  for (Technique t : {Technique::Lists, Technique::SortedLists}) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = 0;
    const TechniqueBuild b = build_technique(c, OffsetSource{}, frags, InsertOptions{});
    EXPECT_TRUE(b.lossless()) << to_string(t);
    EXPECT_EQ(b.attempts.size(), 1u) << to_string(t);
    EXPECT_EQ(b.buffer->capacity(), 5000u) << to_string(t);  // 4000 / 0.8
    EXPECT_EQ(test::traversed_lists(*b.buffer), test::exact_lists(frags, RecordLayout(Layout::L64, 8))) << to_string(t);
    try {
      (void)make_fragment_buffer(c, OffsetSource{});
      ADD_FAILURE() << "a container without fragments took the automatic pool";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("0, automatic, is for build_technique"), std::string::npos) << e.what();
    }
  }
}

TEST(Techniques, TheMemoryModelGivesWhatTheCpuContainersAllocateToTheByte) {
  for (const Extent screen : {Extent{64, 48}, Extent{1000, 3}, Extent{17, 17}})
    for (std::uint32_t block : {1u, 8u, 5u}) {
      TechniqueConfig c = test::technique_config(Technique::Ha, screen);
      c.buffer.block = block;
      c.buffer.table = Extent{screen.x + 3, screen.y + 1};
      const HaBuffer ha = test::make_buffer(c.buffer);
      EXPECT_EQ(memory_model_bytes(c, ha.capacity()), ha.memory_bytes()) << screen.str();
      c.technique = Technique::Lists;
      c.pool_capacity = 777;
      EXPECT_EQ(memory_model_bytes(c, 777), LinkedLists(c).memory_bytes());
      c.technique = Technique::Arrays;
      c.layers = 5;
      EXPECT_EQ(memory_model_bytes(c, 0), FixedArrays(c).memory_bytes());
    }
}

TEST(Techniques, ThePapersTable1IsReproducedByItsFormulas) {
  // Seed 000, Table 1: V = 1024^2, F = 1.5 M: lists 19.7 MiB, HA at 80% 14.3 MiB,
  // paged K = 4 lower bound 16.4 MiB (within the table's rounding of F).
  const std::uint64_t v = 1024 * 1024, f = 1500000;
  const double mib = 1024.0 * 1024.0;
  EXPECT_NEAR(paper_memory_bytes(Technique::Lists, v, f, 1.0, 0) / mib, 19.7, 0.05);
  EXPECT_NEAR(paper_memory_bytes(Technique::Ha, v, f, 0.8, 0) / mib, 14.3, 0.05);
  EXPECT_NEAR(paper_paged_lists_bytes(v, f, 4) / mib, 16.4, 0.1);
  EXPECT_NEAR(paper_memory_bytes(Technique::Ha, v, 10000000, 0.5, 0) / mib, 152.6, 0.1);
}

}  // namespace
}  // namespace habuffer
