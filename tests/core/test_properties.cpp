// SPEC invariants 1-4 as properties over many seeds, streams and
// configurations; determinism across insertion orders and threads (SPEC 9).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"

namespace habuffer {
namespace {

struct Case {
  Extent screen;
  double table_scale;  // table side / screen side
  Layout layout;
  std::uint32_t age_bits;
  std::uint32_t block;
  StreamKind kind;
  double load;
};

std::string describe(const Case& c, std::uint64_t seed) {
  return "screen " + c.screen.str() + " scale " + std::to_string(c.table_scale) + " " + to_string(c.layout) +
         " A=" + std::to_string(c.age_bits) + " B=" + std::to_string(c.block) + " " + to_string(c.kind) +
         " load " + std::to_string(c.load) + " seed " + std::to_string(seed);
}

BufferConfig config_of(const Case& c) {
  const Extent table{static_cast<std::uint32_t>(std::ceil(c.screen.x * c.table_scale)),
                     static_cast<std::uint32_t>(std::ceil(c.screen.y * c.table_scale))};
  return test::config(c.screen, table, c.layout, c.age_bits, c.block);
}

std::vector<Fragment> stream_of(const Case& c, const BufferConfig& cfg, std::uint64_t seed) {
  const auto n = static_cast<std::uint64_t>(c.load * static_cast<double>(cfg.table.area()));
  auto f = test::stream(c.screen, c.kind, n, seed);
  // A few exact duplicates and invalid depths in every stream.
  for (std::size_t i = 0; i + 7 < f.size(); i += 97) f[i + 3] = f[i];
  if (!f.empty()) f[f.size() / 2].depth = std::numeric_limits<float>::quiet_NaN();
  return f;
}

const std::vector<Case> kCases{
    {{64, 48}, 1.0, Layout::L64, 8, 8, StreamKind::Coherent, 0.5},
    {{64, 48}, 1.0, Layout::L32, 8, 8, StreamKind::Random, 0.8},
    {{50, 70}, 1.5, Layout::L64, 6, 3, StreamKind::Coherent, 0.9},
    {{33, 17}, 2.0, Layout::L32, 5, 1, StreamKind::Random, 0.6},
    {{128, 128}, 1.0, Layout::L64, 8, 8, StreamKind::Coherent, 0.95},
    {{1, 40}, 1.0, Layout::L64, 8, 2, StreamKind::Random, 0.7},
    {{40, 1}, 1.3, Layout::L32, 12, 8, StreamKind::Random, 0.7},
};

TEST(Properties, ListsEqualExactDeduplicatedSortedListsAndAccountingHolds) {
  for (const Case& c : kCases)
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SCOPED_TRACE(describe(c, seed));
      const BufferConfig cfg = config_of(c);
      HaBuffer b = test::make_buffer(cfg, seed);
      const auto f = stream_of(c, cfg, seed);
      const Counters n = b.insert(f);
      // Invariant 1: every call accounted for, and the table agrees.
      EXPECT_EQ(n.fragments, f.size());
      EXPECT_EQ(b.count_stored(), n.stored());
      // Invariant 2: every stored record found by traversal of its own pixel, once.
      std::uint64_t traversed = 0;
      std::vector<ListEntry> list;
      for (std::uint32_t y = 0; y < c.screen.y; ++y)
        for (std::uint32_t x = 0; x < c.screen.x; ++x) {
          b.list(x, y, list);
          traversed += list.size();
          // Invariant 3 (first half): sorted nearest first, strictly.
          for (std::size_t i = 1; i < list.size(); ++i)
            ASSERT_TRUE(list[i - 1].code > list[i].code ||
                        (list[i - 1].code == list[i].code && list[i - 1].data > list[i].data));
        }
      EXPECT_EQ(traversed, n.stored());
      // Invariant 3: without failures, lists are exactly the input.
      if (n.failures() == 0) {
        EXPECT_EQ(test::traversed_lists(b), test::exact_lists(f, b.record_layout()));
      }
    }
}

TEST(Properties, ShuffledSerialInsertionGivesTheSameTableBitForBit) {
  for (const Case& c : kCases)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE(describe(c, seed));
      const BufferConfig cfg = config_of(c);
      const auto f = stream_of(c, cfg, seed);
      HaBuffer a = test::make_buffer(cfg, seed), b = test::make_buffer(cfg, seed);
      InsertOptions arrival;  // the order the batch comes in (pixel order has tests of its own)
      arrival.order = InsertOrder::Arrival;
      const Counters na = a.insert(f, arrival);
      const Counters nb = b.insert(test::shuffled(f, seed * 31), arrival);
      ASSERT_EQ(na.failed_iter + nb.failed_iter, 0u);
      EXPECT_EQ(test::table_words(a), test::table_words(b));
      if (na.failures() + nb.failures() == 0) {
        EXPECT_EQ(a.max_age().ages(), b.max_age().ages());
        EXPECT_EQ(na, nb);
      }
    }
}

// Owner-computes (2 and 3 owners, several band heights) and shared-atomic
// insertion reproduce serial insertion bit for bit.
TEST(Properties, ParallelInsertionEqualsSerialInsertion) {
  for (const Case& c : kCases)
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(describe(c, seed));
      const BufferConfig cfg = config_of(c);
      const auto f = stream_of(c, cfg, seed);
      HaBuffer serial = test::make_buffer(cfg, seed);
      const Counters ns = serial.insert(f);
      const auto table = test::table_words(serial);
      for (auto [mode, threads, band] : {std::tuple{InsertMode::OwnerComputes, 2u, 16u},
                                         std::tuple{InsertMode::OwnerComputes, 3u, 1u},
                                         std::tuple{InsertMode::OwnerComputes, 2u, 5u},
                                         std::tuple{InsertMode::Atomic, 2u, 16u}}) {
        HaBuffer par = test::make_buffer(cfg, seed);
        InsertOptions o;
        o.mode = mode;
        o.threads = threads;
        o.band_rows = band;
        const Counters np = par.insert(test::shuffled(f, seed + threads), o);
        ASSERT_EQ(np.failed_iter, 0u);
        EXPECT_EQ(test::table_words(par), table) << "mode " << static_cast<int>(mode) << " threads " << threads;
        EXPECT_EQ(np.stored(), ns.stored());
        if (ns.failures() == 0) {
          EXPECT_EQ(par.max_age().ages(), serial.max_age().ages());
        }
      }
    }
}

TEST(Properties, ParallelInsertionIntoANonEmptyBufferKeepsEarlierRecords) {
  const BufferConfig cfg = test::config({96, 64}, {128, 96});
  const auto f = test::stream({96, 64}, StreamKind::Coherent, 8000, 5);
  HaBuffer serial = test::make_buffer(cfg, 2), par = test::make_buffer(cfg, 2);
  serial.insert(f);
  InsertOptions o;
  o.threads = 2;
  const std::span<const Fragment> all(f);
  par.insert(all.first(3000), o);
  par.insert(all.subspan(3000), o);
  EXPECT_EQ(test::table_words(par), test::table_words(serial));
  EXPECT_EQ(par.max_age().ages(), serial.max_age().ages());
}

TEST(Properties, FarthestOffsetsKeepEveryInvariant) {
  const BufferConfig cfg = test::config({80, 60}, {100, 75});
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    HaBuffer b = test::make_buffer(cfg, seed, OffsetGenerator::Farthest);
    const auto f = test::stream({80, 60}, StreamKind::Coherent, 6000, seed);
    const Counters n = b.insert(f);
    ASSERT_EQ(n.failures(), 0u);
    EXPECT_EQ(test::traversed_lists(b), test::exact_lists(f, b.record_layout()));
  }
}

}  // namespace
}  // namespace habuffer
