// CPU threads for every technique (issue 26): at any thread count each
// technique gives the lists, counters and image one thread gives, and the
// lists' node pool, handed to threads in blocks, runs full exactly as one
// counter does (SPEC invariant 1: every node used before a fragment is
// dropped, every drop and every node asked for counted).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/lossless_build.h"
#include "habuffer/node_blocks.h"
#include "habuffer/parallel.h"
#include "test_support.h"

namespace habuffer {
namespace {

// A technique with the knobs that make it order-dependent or not.
struct Variant {
  std::string name;
  TechniqueConfig config;
};

std::vector<Variant> variants(Extent screen, std::span<const Fragment> frags) {
  const std::uint32_t deepest = test::depth_complexity(frags, screen);
  const auto make = [&](Technique t) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = frags.size();
    c.layers = deepest;
    return c;
  };
  std::vector<Variant> v{{"lists", make(Technique::Lists)},
                         {"sorted-lists", make(Technique::SortedLists)},
                         {"arrays", make(Technique::Arrays)},
                         {"kbuffer", make(Technique::KBuffer)},
                         {"wboit", make(Technique::Wboit)},
                         {"blend", make(Technique::Blend)}};
  // Order-dependent: early termination with saturation, arrays keeping the
  // first K to arrive, a k-buffer whose duplicates meet evictions.
  Variant cull{"sorted-lists:cull=0.9:sat", make(Technique::SortedLists)};
  cull.config.buffer.early_cull_tau = 0.9f;
  cull.config.buffer.saturation = true;
  Variant few{"arrays:k=3", make(Technique::Arrays)};
  few.config.layers = 3;
  Variant kb{"kbuffer:k=3:occ", make(Technique::KBuffer)};
  kb.config.layers = 3;
  kb.config.occupancy = true;
  v.push_back(cull);
  v.push_back(few);
  v.push_back(kb);
  return v;
}

// Everything a caller can see of a container after one batch.
struct Result {
  Counters counters;
  test::ExactLists lists;
  std::vector<glm::vec4> image;
  std::uint64_t stored = 0;
  std::uint64_t requested = 0;  // lists only
};

Result insert_and_read(const TechniqueConfig& c, std::span<const Fragment> frags, const InsertOptions& options) {
  const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(c, OffsetSource{});
  Result r;
  r.counters = b->insert(frags, options);
  r.lists = test::traversed_lists(*b);
  std::vector<glm::vec3> backgrounds(c.buffer.screen.area(), glm::vec3(0.25f, 0.5f, 1.0f));
  r.image = b->composite_image(backgrounds, 1);
  r.stored = b->count_stored();
  if (const auto* lists = dynamic_cast<const LinkedLists*>(b.get())) r.requested = lists->requested();
  return r;
}

void expect_same(const Result& got, const Result& one, const std::string& what) {
  EXPECT_EQ(got.counters, one.counters) << what;
  EXPECT_EQ(got.lists, one.lists) << what;
  EXPECT_TRUE(test::same_bits(got.image, one.image)) << what;
  EXPECT_EQ(got.stored, one.stored) << what;
  EXPECT_EQ(got.requested, one.requested) << what;
}

InsertOptions with_threads(std::uint32_t threads, InsertMode mode = InsertMode::Auto, std::uint32_t band_rows = 16) {
  InsertOptions o;
  o.threads = threads;
  o.mode = mode;
  o.band_rows = band_rows;
  return o;
}

// A stream big enough that the default thread count takes two threads and
// every thread fills several blocks of nodes, with duplicates (hot pixels)
// and invalid depths among them.
std::vector<Fragment> busy_stream(Extent screen) {
  std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 2 * kWorkPerThread, 21);
  const std::vector<Fragment> hot = test::stream(screen, StreamKind::Hot, 6000, 22);
  f.insert(f.end(), hot.begin(), hot.end());
  for (std::size_t i = 0; i < f.size(); i += 997) f[i].depth = i % 2 ? std::nanf("") : 1.5f;
  return test::shuffled(std::move(f), 23);
}

TEST(Threads, EveryTechniqueGivesOneThreadsListsCountersAndImageAtTwoThreeAndTheDefaultThreadCount) {
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = busy_stream(screen);
  for (const Variant& v : variants(screen, frags)) {
    SCOPED_TRACE(v.name);
    const Result one = insert_and_read(v.config, frags, with_threads(1));
    for (std::uint32_t threads : {2u, 3u, 0u})
      expect_same(insert_and_read(v.config, frags, with_threads(threads)), one, "threads " + std::to_string(threads));
    // Bands of one row: neighbouring rows on different threads.
    expect_same(insert_and_read(v.config, frags, with_threads(2, InsertMode::Auto, 1)), one, "bands of one row");
  }
}

TEST(Threads, OrderIndependentTechniquesGiveOneThreadsResultsWithAtomicSlicesOfTheStream) {
  // Atomic: threads split the stream (the GPU's model); only techniques
  // whose result does not depend on arrival order can match one thread.
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = busy_stream(screen);
  for (const Variant& v : variants(screen, frags)) {
    if (v.name.find(':') != std::string::npos || v.name == "kbuffer" || !stores_lists(v.config.technique)) continue;
    SCOPED_TRACE(v.name);
    const Result one = insert_and_read(v.config, frags, with_threads(1));
    for (std::uint32_t threads : {2u, 4u})
      expect_same(insert_and_read(v.config, frags, with_threads(threads, InsertMode::Atomic)), one,
                  "atomic, threads " + std::to_string(threads));
  }
}

// The valid fragments of `frags`.
std::uint64_t valid(std::span<const Fragment> frags) {
  std::uint64_t n = 0;
  for (const Fragment& f : frags) n += f.depth >= 0.0f && f.depth <= 1.0f ? 1 : 0;
  return n;
}

TEST(Threads, APoolThatRunsFullOnSeveralThreadsFillsEveryNodeAndCountsEveryOtherFragmentDropped) {
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = busy_stream(screen);
  const std::uint64_t capacity = frags.size() * 2 / 5;
  for (Technique t : {Technique::Lists, Technique::SortedLists})
    for (InsertMode mode : {InsertMode::Auto, InsertMode::Atomic})
      for (std::uint32_t threads : {1u, 2u, 4u}) {
        SCOPED_TRACE(to_string(t) + (mode == InsertMode::Atomic ? " atomic" : " auto") + " threads " +
                     std::to_string(threads));
        TechniqueConfig c = test::technique_config(t, screen);
        c.pool_capacity = capacity;
        LinkedLists lists(c);
        const Counters n = lists.insert(frags, with_threads(threads, mode));
        EXPECT_EQ(n.fragments, frags.size());
        EXPECT_EQ(n.invalid, frags.size() - valid(frags));
        EXPECT_GT(n.dropped_pool, 0u);
        EXPECT_EQ(lists.count_stored(), n.stored());
        EXPECT_EQ(lists.requested(), n.stored() + n.dropped_pool + (t == Technique::Lists ? n.duplicates : 0));
        if (t == Technique::Lists) {
          // Every valid fragment asks for a node; duplicates are merged after.
          EXPECT_EQ(n.dropped_pool, valid(frags) - capacity);
          EXPECT_EQ(n.stored() + n.duplicates, capacity);
          EXPECT_EQ(lists.requested(), valid(frags));
        } else {
          EXPECT_EQ(n.stored(), capacity);  // duplicates take no node
        }
      }
}

TEST(Threads, SmallBatchesOnTwoThreadsUseTheNodesEarlierBatchesLeftInTheirBlocks) {
  // Each batch leaves part of two blocks unused; a later batch hands those
  // nodes out first, so the pool still fills exactly.
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = busy_stream(screen);
  const std::uint64_t capacity = frags.size() / 2;
  for (Technique t : {Technique::Lists, Technique::SortedLists}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = capacity;
    LinkedLists lists(c);
    Counters n;
    const std::span<const Fragment> all(frags);
    for (std::size_t i = 0; i < all.size(); i += 1500)
      n += lists.insert(all.subspan(i, std::min<std::size_t>(1500, all.size() - i)), with_threads(2));
    EXPECT_EQ(lists.count_stored(), n.stored());
    EXPECT_GT(n.dropped_pool, 0u);
    if (t == Technique::Lists) {
      EXPECT_EQ(n.stored() + n.duplicates, capacity);
      EXPECT_EQ(n.dropped_pool, valid(frags) - capacity);
      EXPECT_EQ(lists.requested(), valid(frags));
    } else {
      EXPECT_EQ(n.stored(), capacity);
      EXPECT_EQ(lists.requested(), n.stored() + n.dropped_pool);
    }
  }
}

TEST(Threads, BatchesThatLeaveThePoolRoomGiveOneBatchsListsAtTwoThreads) {
  const Extent screen{64, 48};
  const std::vector<Fragment> frags = busy_stream(screen);
  for (Technique t : {Technique::Lists, Technique::SortedLists}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = frags.size();
    LinkedLists one(c), batches(c);
    const Counters whole = one.insert(frags);
    Counters parts;
    const std::span<const Fragment> all(frags);
    for (std::size_t i = 0; i < all.size(); i += 5000)
      parts += batches.insert(all.subspan(i, std::min<std::size_t>(5000, all.size() - i)), with_threads(2));
    EXPECT_EQ(parts, whole);
    EXPECT_EQ(batches.requested(), one.requested());
    EXPECT_EQ(test::traversed_lists(batches), test::traversed_lists(one));
  }
}

TEST(Threads, AFragmentOffTheScreenIsNamedAndNothingInsertedAtTwoThreads) {
  const Extent screen{64, 48};
  std::vector<Fragment> frags = busy_stream(screen);
  const std::vector<Variant> all = variants(screen, frags);
  const std::size_t first = frags.size() * 3 / 4, second = frags.size() - 5;
  frags[second].y = screen.y;
  frags[first].x = screen.x + 7;
  for (const Variant& v : all) {
    SCOPED_TRACE(v.name);
    const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(v.config, OffsetSource{});
    try {
      b->insert(frags, with_threads(2));
      ADD_FAILURE() << "nothing thrown";
    } catch (const std::out_of_range& e) {
      EXPECT_NE(std::string(e.what()).find("fragment " + std::to_string(first) + " "), std::string::npos) << e.what();
    }
    EXPECT_EQ(b->count_stored(), 0u);
  }
}

TEST(NodePool, HandsOutSpareRangesFirstThenFreshBlocksAndNothingBeyondTheCapacity) {
  std::uint32_t fresh = 100;
  const std::vector<NodeRange> spare{{10, 20}, {40, 45}};
  NodePool pool(&fresh, 2600, spare, 1024);
  EXPECT_EQ(pool.take(), (NodeRange{10, 20}));
  EXPECT_EQ(pool.take(), (NodeRange{40, 45}));
  EXPECT_EQ(pool.take(), (NodeRange{100, 1124}));
  EXPECT_EQ(pool.take(), (NodeRange{1124, 2148}));
  EXPECT_EQ(pool.take(), (NodeRange{2148, 2600}));  // what is left
  EXPECT_TRUE(pool.take().empty());
  EXPECT_EQ(fresh, 2600u);  // the counter never runs past the capacity
  const std::vector<NodeRange> blocks{{2000, 2100}, {}};
  EXPECT_EQ(pool.unused(blocks), (std::vector<NodeRange>{{2000, 2100}}));
}

TEST(NodePool, TheRangeEndingAtTheCounterGoesBackToItSoOneThreadLeavesNoSpareRange) {
  std::uint32_t fresh = 3072;
  std::vector<NodeRange> spare{{500, 1024}, {2900, 3072}, {3000, 3000}, {2048, 2900}};
  return_to_counter(spare, &fresh);
  EXPECT_EQ(fresh, 2048u);  // [2900, 3072), then [2048, 2900)
  EXPECT_EQ(spare, (std::vector<NodeRange>{{500, 1024}}));
}

TEST(Threads, TheDefaultCountTakesOneThreadPerWorkShareAndExplicitCountsAreHonoured) {
  const std::uint32_t all = default_concurrency();
  EXPECT_EQ(resolve_threads(0, 0), 1u);
  EXPECT_EQ(resolve_threads(0, kWorkPerThread - 1), 1u);
  EXPECT_EQ(resolve_threads(0, 2 * kWorkPerThread), std::min(all, 2u));
  EXPECT_EQ(resolve_threads(0, UINT64_MAX), all);
  EXPECT_EQ(resolve_threads(0), all);
  EXPECT_EQ(resolve_threads(3, 1), 3u);
  EXPECT_THROW((void)resolve_threads(kMaxThreads + 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
