// Paged lists (technique paged-lists, seed 000's "paged lists"): linked
// lists whose nodes come in pages of K = 4 per pixel, sorted after the
// gather. The same lists and counters as the HA-buffer when nothing drops,
// over several insert calls too (the sort restarts each list at its highest
// node so a later call finds its page), a full pool counted and grown by
// lossless mode, the memory model to the byte and seed 000's formula, and
// the lists of one thread on several.
#include <gtest/gtest.h>

#include <array>
#include <latch>
#include <map>
#include <thread>

#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "test_support.h"

namespace habuffer {
namespace {

constexpr std::uint32_t K = kPagedListsPageNodes;

TechniqueConfig paged_config(Extent screen, std::uint64_t pool, Layout layout = Layout::L64, std::uint32_t age_bits = 8) {
  TechniqueConfig c = test::technique_config(Technique::PagedLists, screen, layout, age_bits);
  c.pool_capacity = pool;
  return c;
}

// The nodes a gather of `frags` asks for on one thread: a page per K fragments of each pixel (valid ones).
std::uint64_t pages_in_nodes(std::span<const Fragment> frags, Extent screen) {
  std::map<std::uint64_t, std::uint64_t> n;
  for (const Fragment& f : frags)
    if (RecordLayout::depth_valid(f.depth)) ++n[f.x + std::uint64_t{f.y} * screen.x];
  std::uint64_t nodes = 0;
  for (const auto& [pixel, count] : n) nodes += (count + K - 1) / K * K;
  return nodes;
}

TEST(PagedLists, GiveTheExactListsAndTheHaBuffersCountersOverSeedsStreamsAndLayouts) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    for (StreamKind kind : {StreamKind::Random, StreamKind::Coherent, StreamKind::Stacked, StreamKind::Hot}) {
      const Extent screen{11 + 6 * static_cast<std::uint32_t>(seed), 7 + 3 * static_cast<std::uint32_t>(seed)};
      const Layout layout = seed % 2 == 0 ? Layout::L32 : Layout::L64;
      // Few age bits only where the HA-buffer holds every pixel's records.
      const std::uint32_t age_bits = seed == 3 && (kind == StreamKind::Random || kind == StreamKind::Coherent) ? 5 : 8;
      std::vector<Fragment> frags = test::stream(screen, kind, 600 + 250 * seed, seed);
      frags.push_back(frags.front());  // an exact duplicate
      const TechniqueConfig c = paged_config(screen, frags.size() * K, layout, age_bits);
      PagedLists paged(c);
      const Counters counters = paged.insert(frags);
      const std::string what = "seed " + std::to_string(seed) + " kind " + std::to_string(static_cast<int>(kind));
      EXPECT_EQ(test::traversed_lists(paged), test::exact_lists(frags, c.buffer.record_layout())) << what;
      const BuildResult ha = build(c.buffer, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
      ASSERT_EQ(ha.counters.failures(), 0u) << what;
      EXPECT_EQ(counters, ha.counters) << what;
      EXPECT_GE(counters.duplicates, 1u) << what;
      EXPECT_EQ(paged.count_stored(), counters.stored()) << what;
      // One thread: every page asked for is linked, a page per K fragments of a pixel.
      EXPECT_EQ(paged.requested(), pages_in_nodes(frags, screen)) << what;
      EXPECT_EQ(paged.wasted_pages(), 0u) << what;
      const std::vector<glm::vec3> backgrounds(screen.area(), glm::vec3(0.25f, 0.5f, 0.75f));
      EXPECT_TRUE(test::same_bits(paged.composite_image(backgrounds), ha.buffer.composite_image(backgrounds))) << what;
    }
}

TEST(PagedLists, SeveralInsertCallsAndListsLongerThanThePrivateArrayStayExact) {
  const Extent screen{9, 7};
  std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 2500, 7);
  SplitMix64 rng(11);
  for (int i = 0; i < 150; ++i)  // one pixel far beyond HABUFFER_SORT_LOCAL, with duplicates
    frags.push_back({4, 3, static_cast<float>(rng.below(120)) / 131.0f, 0x30405000u + static_cast<std::uint32_t>(rng.below(3))});
  frags = test::shuffled(frags, 5);
  const TechniqueConfig c = paged_config(screen, frags.size() * K);
  const test::ExactLists exact = test::exact_lists(frags, c.buffer.record_layout());
  ASSERT_GT(exact.at({4, 3}).size(), HABUFFER_SORT_LOCAL);
  PagedLists whole(c);
  const Counters all = whole.insert(frags);
  EXPECT_EQ(test::traversed_lists(whole), exact);
  // In three calls: each sorts, and the next links into the pages the sort left.
  PagedLists parts(c);
  Counters sum;
  const std::size_t a = frags.size() / 3, b = 2 * frags.size() / 3;
  sum += parts.insert(std::span(frags).subspan(0, a));
  sum += parts.insert(std::span(frags).subspan(a, b - a));
  sum += parts.insert(std::span(frags).subspan(b));
  EXPECT_EQ(test::traversed_lists(parts), exact);
  EXPECT_EQ(sum.stored() + sum.duplicates, all.stored() + all.duplicates);
  EXPECT_EQ(parts.count_stored(), all.stored());
  EXPECT_LE(parts.requested(), whole.requested() + std::uint64_t{K} * screen.area() * 2);
  // After a clear, the container is as new.
  EXPECT_EQ(parts.clear(), all.stored());
  EXPECT_EQ(parts.count_stored(), 0u);
  EXPECT_EQ(parts.requested(), 0u);
  EXPECT_EQ(parts.insert(frags), all);
  EXPECT_EQ(test::traversed_lists(parts), exact);
}

TEST(PagedLists, AFullPoolDropsAndCountsAndLosslessModeGrowsUntilNothingDrops) {
  const Extent screen{24, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 3000, 4);
  const std::uint64_t needed = pages_in_nodes(frags, screen);
  const TechniqueConfig c = paged_config(screen, 1002);  // 250 pages (the last 2 nodes unused)
  PagedLists small(c);
  const Counters counters = small.insert(frags);
  EXPECT_GT(counters.dropped_pool, 0u);
  EXPECT_EQ(counters.stored() + counters.duplicates + counters.dropped_pool + counters.invalid, frags.size());
  EXPECT_EQ(small.count_stored(), counters.stored());
  EXPECT_LE(small.count_stored(), 1000u);
  EXPECT_GE(small.requested(), needed);  // every dropped fragment asked for a page
  EXPECT_EQ(small.growth_need().nodes_requested, small.requested());
  // What it kept are some of the exact lists' entries, sorted.
  const test::ExactLists exact = test::exact_lists(frags, c.buffer.record_layout());
  for (const auto& [pixel, list] : test::traversed_lists(small)) {
    const auto& all = exact.at(pixel);
    for (std::size_t i = 0; i < list.size(); ++i) {
      EXPECT_NE(std::find(all.begin(), all.end(), list[i]), all.end());
      if (i > 0) {
        EXPECT_TRUE(list[i - 1].code > list[i].code || (list[i - 1].code == list[i].code && list[i - 1].data > list[i].data));
      }
    }
  }

  const TechniqueBuild lossless = build_technique(c, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 4);
  EXPECT_EQ(lossless.counters.failures(), 0u);
  ASSERT_GE(lossless.attempts.size(), 2u);
  EXPECT_EQ(lossless.attempts[0].capacity, 1002u);
  EXPECT_GE(lossless.buffer->capacity(), needed);
  EXPECT_EQ(test::traversed_lists(*lossless.buffer), exact);
  EXPECT_FALSE(descriptor(Technique::PagedLists).lossless_hint.empty());

  // The automatic pool (0) is grown too.
  TechniqueConfig automatic = c;
  automatic.pool_capacity = 0;
  const TechniqueBuild autob = build_technique(automatic, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 4);
  EXPECT_EQ(autob.counters.failures(), 0u);
  EXPECT_EQ(test::traversed_lists(*autob.buffer), exact);
}

TEST(PagedLists, TheMemoryModelIsWhatItAllocatesAndThePaperFormulaIsSeed000sPagedLists) {
  for (const Extent screen : {Extent{40, 30}, Extent{7, 19}})
    for (std::uint64_t pool : {1ull, 333ull, 4096ull}) {
      const TechniqueConfig c = paged_config(screen, pool);
      const PagedLists b(c);
      EXPECT_EQ(memory_model_bytes(c, pool), b.memory_bytes());
      EXPECT_EQ(b.memory_bytes(), screen.area() * 4 + pool * 12 + 8);
      EXPECT_EQ(memory_model_bytes(b), b.memory_bytes());
    }
  const TechniqueDescriptor& d = descriptor(Technique::PagedLists);
  EXPECT_EQ(d.name, "paged-lists");
  EXPECT_EQ(d.capacity, CapacityKind::PoolNodes);
  EXPECT_TRUE(d.exact);
  EXPECT_TRUE(d.takes("pool") && d.takes("lossless") && d.takes("max-attempts"));
  EXPECT_FALSE(d.takes("early-cull"));
  // Seed 000's Table 1, "paged, K = 4, lower bound" (MiB, V = 1024^2).
  const std::uint64_t pixels = 1024ull * 1024ull;
  const std::pair<std::uint64_t, double> table1[] = {{850000, 11.5}, {1500000, 16.4}, {10000000, 81.3}};
  for (const auto& [f, mib] : table1) {
    EXPECT_DOUBLE_EQ(d.paper_memory_bytes(pixels, f, 1.0, 16), paper_paged_lists_bytes(pixels, f, 4));
    EXPECT_NEAR(d.paper_memory_bytes(pixels, f, 1.0, 16) / (1024.0 * 1024.0), mib, 0.05) << f;
  }
}

TEST(PagedLists, ParallelInsertCallsGiveTheListsOfOneThread) {
  const Extent screen{37, 29};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 12000, 9);
  const TechniqueConfig c = paged_config(screen, frags.size() * K);
  PagedLists one(c);
  const Counters expected = one.insert(frags);
  const test::ExactLists lists = test::traversed_lists(one);
  EXPECT_EQ(lists, test::exact_lists(frags, c.buffer.record_layout()));
  for (InsertMode mode : {InsertMode::Auto, InsertMode::Atomic})
    for (std::uint32_t threads : {2u, 3u}) {
      PagedLists many(c);
      InsertOptions o;
      o.threads = threads;
      o.mode = mode;
      o.band_rows = 2;
      EXPECT_EQ(many.insert(frags, o), expected) << threads << " threads, mode " << static_cast<int>(mode);
      EXPECT_EQ(test::traversed_lists(many), lists) << threads << " threads, mode " << static_cast<int>(mode);
      // Pages a race left unused are counted: what was asked for is what one thread asks, and K per waste.
      EXPECT_EQ(many.requested(), one.requested() + many.wasted_pages() * K);
      // A second call into the same lists (sorted, each restarted at its highest node).
      many.insert(frags, o);
      EXPECT_EQ(test::traversed_lists(many), lists);
    }
}

TEST(PagedLists, ImportedStateIsCheckedAndRestartedAtTheHighestNode) {
  const Extent screen{4, 2};
  const TechniqueConfig c = paged_config(screen, 16);
  PagedLists b(c);
  std::vector<std::uint32_t> heads(8, 0), next(16, 0);
  std::vector<glm::uvec2> entries(16, glm::uvec2(0));
  // Pixel 0: nodes 1 (nearest), 0, 2 (links 2, 1, 3): sorted, not started at its highest node.
  entries[1] = {0x300u << 8, 1u};
  entries[0] = {0x200u << 8, 1u};
  entries[2] = {0x100u << 8, 1u};
  heads[0] = 2;
  next[1] = 1;
  next[0] = 3;
  next[2] = 0;
  b.import_state(heads, entries, next, 4);
  std::vector<ListEntry> list;
  b.list(0, 0, list);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].code, 0x300u << 8);
  EXPECT_EQ(list[2].code, 0x100u << 8);
  // The next fragment of pixel 0 takes node 3, the last of its page.
  b.insert(std::vector<Fragment>{{0, 0, 0.5f, 0x11223344u}});
  EXPECT_EQ(b.count_stored(), 4u);
  EXPECT_EQ(b.requested(), 4u);
  // A page shared by two pixels is refused.
  entries[3] = {0x50u << 8, 2u};
  heads[1] = 4;
  EXPECT_THROW(b.import_state(heads, entries, next, 4), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer

namespace habuffer {
namespace {

// The lock-free insertion itself, on threads racing for a few pixels (no
// insert-call machinery between them): the exact lists once sorted, and
// every page asked for either linked or counted wasted.
TEST(PagedLists, ParallelKernelsRacingForFewPixelsLinkEveryFragmentAndCountEveryPage) {
  const Extent screen{3, 2};
  constexpr std::uint32_t kThreads = 4;
  std::vector<Fragment> frags = test::grid_stream(screen, 200000, 21, 1);  // enough for the threads to overlap
  const TechniqueConfig c = paged_config(screen, frags.size() * K);
  const KernelUniforms params = kernel_uniforms(c);
  std::vector<std::uint32_t> heads(screen.area(), 0), next(c.pool_capacity, 0);
  std::vector<glm::uvec2> entries(c.pool_capacity);
  std::uint32_t counter = 0, wasted = 0;
  const PagedListsBuffers b{heads.data(), entries.data(), next.data(), &counter, &wasted};
  std::vector<std::array<std::uint64_t, HABUFFER_OUTCOME_COUNT>> tallies(kThreads);
  std::vector<std::thread> threads;
  std::latch start(kThreads);
  for (std::uint32_t t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      PagedListsKernel<true> k(params, b);
      start.arrive_and_wait();
      for (std::size_t i = t; i < frags.size(); i += kThreads)
        ++tallies[t][k.pl_insert_fragment(glm::uvec2(frags[i].x, frags[i].y), frags[i].depth, frags[i].coverage, frags[i].rgba)];
    });
  for (std::thread& th : threads) th.join();
  std::uint64_t stored = 0;
  for (const auto& tally : tallies) stored += tally[HABUFFER_STORED];
  EXPECT_EQ(stored, frags.size());
  ::testing::Test::RecordProperty("wasted_pages", static_cast<int>(wasted));
  // Each pixel links a page per K of its fragments; the rest was lost to races.
  EXPECT_EQ(counter, pages_in_nodes(frags, screen) + std::uint64_t{wasted} * K);
  PagedListsKernel<false> sorter(params, b);
  std::uint64_t merged = 0;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) merged += sorter.pl_sort_pixel(glm::uvec2(x, y));
  test::ExactLists lists;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      for (std::uint32_t l = heads[x + y * screen.x]; l != 0; l = next[l - 1]) {
        lists[{x, y}].push_back({0, entries[l - 1].x, entries[l - 1].y});
        if (l != heads[x + y * screen.x]) {
          EXPECT_LT(l, heads[x + y * screen.x]) << "the head is the list's highest node";
        }
      }
  const test::ExactLists exact = test::exact_lists(frags, c.buffer.record_layout());
  EXPECT_EQ(lists, exact);
  std::uint64_t distinct = 0;
  for (const auto& [pixel, list] : exact) distinct += list.size();
  EXPECT_EQ(merged, frags.size() - distinct);
}

}  // namespace
}  // namespace habuffer
