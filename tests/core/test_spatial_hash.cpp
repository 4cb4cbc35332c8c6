// The spatial hash (habuffer/spatial/spatial_hash.h): every key found with
// its value and absent keys missed at every load, one key once by each rule,
// the same table for every order and thread count, erase, growth and
// shrink, 3D keys folded, and the adversarial key sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "habuffer/key_experiment.h"
#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::spatial {
namespace {

using Key = glm::uvec3;

struct KeyLess {
  bool operator()(const Key& a, const Key& b) const {
    return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x);
  }
};

// `n` distinct random keys of the domain, and `absent` more not among them.
std::pair<std::vector<Key>, std::vector<Key>> random_keys(Domain d, std::size_t n, std::size_t absent,
                                                           std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::set<Key, KeyLess> seen;
  std::vector<Key> in, out;
  while (in.size() + out.size() < n + absent) {
    const Key k(static_cast<std::uint32_t>(rng() % d.x), static_cast<std::uint32_t>(rng() % d.y),
                static_cast<std::uint32_t>(rng() % d.z));
    if (!seen.insert(k).second) continue;
    (in.size() < n ? in : out).push_back(k);
  }
  return {in, out};
}

std::vector<std::uint32_t> values_of(const std::vector<Key>& keys) {
  std::vector<std::uint32_t> v(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) v[i] = keys[i].x * 2654435761u ^ keys[i].y * 40503u ^ keys[i].z;
  return v;
}

SpatialHashConfig fixed(Domain d, std::uint32_t threads = 2) {
  SpatialHashConfig c;
  c.domain = d;
  c.adaptive = false;
  c.threads = threads;
  return c;
}

void expect_counts_add_up(const InsertReport& r) {
  EXPECT_EQ(r.calls, r.stored + r.duplicates + r.failed_age + r.failed_iter);
}

TEST(SpatialHash, EveryKeyIsFoundWithItsValueAndAbsentKeysAreMissedAtEveryLoadUpTo099) {
  const Domain d{2048, 1024};
  const auto [keys, absent] = random_keys(d, 40000, 200000, 7);
  const std::vector<std::uint32_t> values = values_of(keys);
  for (const double load : {0.5, 0.8, 0.9, 0.95, 0.99}) {
    SCOPED_TRACE(load);
    SpatialHash h(fixed(d));
    h.reserve(keys.size(), load);
    const InsertReport r = h.insert(keys, values);
    expect_counts_add_up(r);
    EXPECT_EQ(r.lost, 0u);
    EXPECT_EQ(h.size(), keys.size());
    EXPECT_NEAR(h.load(), load, 0.02);
    std::vector<std::uint32_t> got(keys.size());
    std::vector<std::uint8_t> found(keys.size());
    EXPECT_EQ(h.find(keys, got, found), keys.size());
    EXPECT_EQ(got, values);
    std::vector<std::uint32_t> miss_values(absent.size());
    std::vector<std::uint8_t> miss_found(absent.size());
    EXPECT_EQ(h.find(absent, miss_values, miss_found), 0u);
    EXPECT_EQ(std::count(miss_found.begin(), miss_found.end(), 1), 0);
    EXPECT_EQ(h.find(keys[123]), values[123]);
    EXPECT_FALSE(h.contains(absent[5]));
  }
}

TEST(SpatialHash, TheTableIsTheSameForEveryInsertionOrderAndThreadCountParallel) {
  const Domain d{512, 512};
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    auto [keys, unused] = random_keys(d, 60000, 0, seed);
    // Duplicates too: every 7th key again with another value.
    std::vector<std::uint32_t> values = values_of(keys);
    for (std::size_t i = 0; i < 8000; ++i) {
      keys.push_back(keys[i * 7]);
      values.push_back(static_cast<std::uint32_t>(i * 977));
    }
    for (const DuplicateRule rule : {DuplicateRule::Max, DuplicateRule::Min, DuplicateRule::First, DuplicateRule::Last}) {
      SCOPED_TRACE(to_string(rule) + " seed " + std::to_string(seed));
      std::vector<std::uint64_t> reference;
      for (const std::uint32_t threads : {1u, 2u, 4u}) {
        SpatialHashConfig c = fixed(d, threads);
        c.rule = rule;
        SpatialHash h(c);
        h.reserve(60000, 0.95);
        std::vector<Key> k = keys;
        std::vector<std::uint32_t> v = values;
        if (threads == 4 && rule != DuplicateRule::First && rule != DuplicateRule::Last) {
          // Max and Min do not depend on the batch's order: shuffle it.
          std::vector<std::size_t> order(k.size());
          std::iota(order.begin(), order.end(), 0);
          std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
          for (std::size_t i = 0; i < order.size(); ++i) {
            k[i] = keys[order[i]];
            v[i] = values[order[i]];
          }
        }
        const InsertReport r = h.insert(k, v);
        EXPECT_EQ(r.duplicates, 8000u);
        EXPECT_EQ(h.size(), 60000u);
        const std::vector<std::uint64_t> table(h.table().begin(), h.table().end());
        if (reference.empty()) reference = table;
        else EXPECT_TRUE(table == reference) << threads << " threads";
      }
    }
  }
}

TEST(SpatialHash, EachRuleKeepsItsValueWithinABatchAndAcrossBatches) {
  const Domain d{64, 64};
  const std::vector<Key> keys = {{1, 1, 0}, {2, 2, 0}, {1, 1, 0}, {1, 1, 0}, {3, 3, 0}};
  const std::vector<std::uint32_t> values = {5, 7, 9, 2, 1};
  const std::map<DuplicateRule, std::uint32_t> want = {
      {DuplicateRule::Max, 9}, {DuplicateRule::Min, 2}, {DuplicateRule::First, 5}, {DuplicateRule::Last, 2}};
  for (const auto& [rule, expected] : want) {
    SCOPED_TRACE(to_string(rule));
    SpatialHashConfig c = fixed(d);
    c.rule = rule;
    SpatialHash h(c, 16);
    const InsertReport r = h.insert(keys, values);
    EXPECT_EQ(r.duplicates, 2u);
    EXPECT_EQ(r.stored, 3u);
    EXPECT_EQ(h.find({1, 1, 0}), expected);
    EXPECT_EQ(h.find({2, 2, 0}), 7u);
    // Across batches: the table's value is "earlier" than the batch's.
    const InsertReport again = h.insert({1, 1, 0}, 4u);
    EXPECT_EQ(again.duplicates, 1u);
    const std::uint32_t after = rule == DuplicateRule::Max   ? std::max(expected, 4u)
                                : rule == DuplicateRule::Min ? std::min(expected, 4u)
                                : rule == DuplicateRule::First ? expected
                                                               : 4u;
    EXPECT_EQ(h.find({1, 1, 0}), after);
    EXPECT_EQ(h.size(), 3u);
  }
  EXPECT_EQ(parse_duplicate_rule("last"), DuplicateRule::Last);
  EXPECT_FALSE(parse_duplicate_rule("newest").has_value());
}

TEST(SpatialHash, EraseLeavesEveryOtherKeyAndTheKeyInsertedAgainComesBack) {
  const Domain d{300, 200};
  const auto [keys, absent] = random_keys(d, 20000, 1000, 11);
  const std::vector<std::uint32_t> values = values_of(keys);
  SpatialHash h(fixed(d));
  h.reserve(keys.size(), 0.9);
  h.insert(keys, values);
  std::vector<Key> gone(keys.begin(), keys.begin() + 5000);
  EXPECT_EQ(h.erase(gone), 5000u);
  EXPECT_FALSE(h.erase(gone[0]));
  EXPECT_FALSE(h.erase(absent[0]));
  EXPECT_EQ(h.size(), 15000u);
  EXPECT_EQ(h.stats().tombstones, 5000u);
  for (std::size_t i = 0; i < keys.size(); i += 7)
    EXPECT_EQ(h.find(keys[i]), i < 5000 ? std::nullopt : std::optional<std::uint32_t>(values[i])) << i;
  // Inserted again: over its tombstone (revived), not twice.
  const InsertReport r = h.insert(gone[0], 42u);
  EXPECT_EQ(r.stored, 1u);
  EXPECT_EQ(r.tombstones_dropped, 1u);
  EXPECT_EQ(h.find(gone[0]), 42u);
  EXPECT_EQ(h.stats().tombstones, 4999u);
  h.compact();
  EXPECT_EQ(h.stats().tombstones, 0u);
  EXPECT_EQ(h.size(), 15001u);
  for (std::size_t i = 5000; i < keys.size(); i += 5) EXPECT_EQ(h.find(keys[i]), values[i]);
  EXPECT_EQ(h.entries().size(), 15001u);
}

TEST(SpatialHash, AdaptiveSizingGrowsAndShrinksByThe80And30RuleKeepingEveryKey) {
  const Domain d{1000, 1000};
  const auto [keys, absent] = random_keys(d, 50000, 0, 5);
  SpatialHashConfig c;
  c.domain = d;
  c.threads = 2;
  SpatialHash h(c);
  InsertReport all;
  for (std::size_t at = 0; at < keys.size(); at += 1000) {
    all += h.insert(std::span<const Key>(keys).subspan(at, 1000));
    EXPECT_LE(h.load(), c.grow_at + 1e-9);
  }
  EXPECT_GT(all.rehashes, 3u);
  EXPECT_EQ(h.size(), keys.size());
  for (std::size_t i = 0; i < keys.size(); i += 3) EXPECT_TRUE(h.contains(keys[i]));
  const std::uint64_t big = h.slots();
  h.erase(std::span<const Key>(keys).subspan(0, 45000));
  EXPECT_LT(h.slots(), big / 4);
  EXPECT_GE(h.load(), c.shrink_at);
  EXPECT_EQ(h.size(), 5000u);
  for (std::size_t i = 45000; i < keys.size(); ++i) ASSERT_TRUE(h.contains(keys[i])) << i;
}

// Keys that collide at every offset: the same position, so the same probes;
// AMAX of them fit (one per age), the next fails, and the lossless table grows.
TEST(SpatialHash, KeysCollidingAtEveryOffsetGrowTheTableLosslesslyOrAreCountedLost) {
  const Domain d{1u << 16, 4};
  SpatialHashConfig c = fixed(d, 1);
  c.age_bits = 4;  // AMAX 15
  SpatialHash probe(c, 4);
  const Extent t = probe.table_extent();
  std::vector<Key> keys;
  for (std::uint32_t j = 0; j < 40; ++j) keys.push_back({3 + j * t.x, 1, 0});
  SpatialHash lossless(c, 4);
  const InsertReport r = lossless.insert(keys);
  EXPECT_GT(r.failed_age, 0u);
  EXPECT_EQ(r.lost, 0u);
  EXPECT_GT(r.rehashes, 0u);
  EXPECT_EQ(lossless.size(), keys.size());
  for (const Key& k : keys) EXPECT_TRUE(lossless.contains(k));
  c.lossless = false;
  SpatialHash lossy(c, 4);
  const InsertReport l = lossy.insert(keys);
  EXPECT_GT(l.lost, 0u);
  EXPECT_EQ(lossy.size() + l.lost, keys.size());
  expect_counts_add_up(l);
}

TEST(SpatialHash, AllKeysInOneRowTheDomainsCornersOneKeyAndAFullTable) {
  const Domain d{4096, 4096};
  std::vector<Key> row;
  for (std::uint32_t x = 0; x < 4096; ++x) row.push_back({x, 17, 0});
  SpatialHash h(fixed(d));
  h.reserve(row.size(), 0.95);
  h.insert(row);
  for (const Key& k : row) ASSERT_TRUE(h.contains(k));
  EXPECT_FALSE(h.contains({0, 18, 0}));

  const std::vector<Key> corners = {{0, 0, 0}, {4095, 0, 0}, {0, 4095, 0}, {4095, 4095, 0}};
  SpatialHash c(fixed(d), 4);
  c.insert(corners, std::vector<std::uint32_t>{1, 2, 3, 0xFFFFFFFFu});
  EXPECT_EQ(c.find({4095, 4095, 0}), 0xFFFFFFFFu);
  EXPECT_EQ(c.find({0, 0, 0}), 1u);

  SpatialHash one(fixed(d), 1);
  one.insert({77, 88, 0}, 5u);
  EXPECT_EQ(one.size(), 1u);
  EXPECT_EQ(one.entries(), (std::vector<Entry>{{{77, 88, 0}, 5u}}));
  EXPECT_FALSE(one.contains({88, 77, 0}));

  // Every key of a small domain: the table is the domain, load 1.
  const Domain small{40, 30};
  std::vector<Key> every;
  for (std::uint32_t y = 0; y < 30; ++y)
    for (std::uint32_t x = 0; x < 40; ++x) every.push_back({x, y, 0});
  SpatialHash full(fixed(small), 1200);
  full.insert(every, values_of(every));
  EXPECT_EQ(full.slots(), 1200u);
  EXPECT_DOUBLE_EQ(full.load(), 1.0);
  std::vector<std::uint32_t> got(every.size());
  std::vector<std::uint8_t> found(every.size());
  EXPECT_EQ(full.find(every, got, found), every.size());
  EXPECT_EQ(got, values_of(every));
}

TEST(SpatialHash, ThreeDimensionalKeysFoldOntoTheTableAndNeighbourhoodsAreExact) {
  const Domain d{64, 48, 40};
  const FoldedDomain f(d);
  for (const Key k : {Key{0, 0, 0}, Key{63, 47, 39}, Key{5, 9, 17}})
    EXPECT_EQ(f.unfold(f.fold(k)), k);
  EXPECT_LE(f.folded().x, 64u * 40u);
  const auto [keys, absent] = random_keys(d, 30000, 0, 9);
  std::set<Key, KeyLess> present(keys.begin(), keys.end());
  SpatialHash h(fixed(d));
  h.reserve(keys.size(), 0.9);
  h.insert(keys, values_of(keys));
  for (const Key centre : {Key{0, 0, 0}, Key{32, 20, 20}, Key{63, 47, 39}}) {
    std::vector<Entry> got = h.neighbourhood(centre, 2);
    std::vector<Key> want;
    for (std::uint32_t z = centre.z >= 2 ? centre.z - 2 : 0; z <= std::min(39u, centre.z + 2); ++z)
      for (std::uint32_t y = centre.y >= 2 ? centre.y - 2 : 0; y <= std::min(47u, centre.y + 2); ++y)
        for (std::uint32_t x = centre.x >= 2 ? centre.x - 2 : 0; x <= std::min(63u, centre.x + 2); ++x)
          if (present.count({x, y, z})) want.push_back({x, y, z});
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].key, want[i]);
  }
  std::vector<Entry> all = h.entries();
  EXPECT_EQ(all.size(), keys.size());
  for (const Entry& e : all) EXPECT_TRUE(present.count(e.key));
}

TEST(SpatialHash, BadKeysAndSettingsAreRefusedNamingThem) {
  SpatialHash h(fixed({100, 50}));
  const auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(message([&] { h.insert({100, 0, 0}); }), "spatial hash: key (100, 0, 0) is outside the domain 100x50");
  const std::vector<Key> batch = {{1, 1, 0}, {2, 2, 0}, {3, 50, 0}};
  EXPECT_EQ(message([&] { h.insert(batch); }), "spatial hash: key 2 (3, 50, 0) is outside the domain 100x50");
  EXPECT_EQ(h.size(), 0u);  // nothing of the batch went in
  EXPECT_EQ(message([&] { (void)h.find({0, 0, 1}); }), "spatial hash: key (0, 0, 1) is outside the domain 100x50");
  EXPECT_NE(message([&] { h.insert(batch, std::vector<std::uint32_t>{1}); }).find("3 keys but 1 values"),
            std::string::npos);
  SpatialHashConfig c = fixed({0, 5});
  EXPECT_NE(message([&] { SpatialHash x(c); }).find("domain 0x5 has a zero side"), std::string::npos);
  c = fixed({8, 8});
  c.age_bits = 13;
  EXPECT_NE(message([&] { SpatialHash x(c); }).find("age bits 13 outside 4..12"), std::string::npos);
  c = fixed({8, 8});
  c.shrink_at = 0.9;
  EXPECT_NE(message([&] { SpatialHash x(c); }).find("shrink_at"), std::string::npos);
  EXPECT_NE(message([&] { SpatialHash x(fixed({1u << 31, 1u << 31, 16})); }).find("beyond 32-bit"), std::string::npos);
  SpatialHash y(fixed({64, 64}));
  EXPECT_NE(message([&] { y.rehash({65, 1}); }).find("not within the folded domain 64x64"), std::string::npos);
}

// A huge domain with few keys: the table is sized up until the quotients fit
// the record's bits, and stays correct.
TEST(SpatialHash, AHugeDomainWithFewKeysSizesTheTableForItsQuotients) {
  const Domain d{1u << 20, 1u << 20};
  const auto [keys, absent] = random_keys(d, 500, 500, 3);
  SpatialHash h(fixed(d), keys.size());
  EXPECT_GE(h.slots(), (std::uint64_t{1} << 40) >> (31u - h.config().age_bits));
  h.insert(keys, values_of(keys));
  EXPECT_LE(h.stats().quotient_bits, 31u - h.config().age_bits);
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_EQ(h.find(keys[i]), values_of(keys)[i]);
  for (const Key& k : absent) EXPECT_FALSE(h.contains(k));
  try {
    SpatialHash x(fixed({4000000000u, 4000000000u}), 10);
    ADD_FAILURE() << "a domain of 1.6e19 keys accepted with 23 quotient bits";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("for its quotients to fit 23 bits"), std::string::npos) << e.what();
  }
}

// The thread count has the CLI's bound (--threads 0..1024) in the config
// and in set_threads, and a table's finds run on the threads set after it
// was made (a loaded table's, habuffer hash query --threads).
TEST(SpatialHash, ThreadsAboveTheLimitAreRefusedAndFindsRunOnTheThreadsSetLaterParallel) {
  SpatialHashConfig c = fixed({64, 64});
  c.threads = 5000;
  try {
    SpatialHash x(c);
    ADD_FAILURE() << "5000 threads accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("threads 5000 outside 0..1024"), std::string::npos) << e.what();
  }
  c.threads = 1024;
  EXPECT_NO_THROW(SpatialHash{c});
  const Domain d{512, 512};
  const std::vector<Key> keys = random_keys(d, 20000, 0, 8).first;
  SpatialHash h(fixed(d, 1), keys.size());
  h.insert(keys, values_of(keys));
  EXPECT_THROW(h.set_threads(1025), std::invalid_argument);
  EXPECT_EQ(h.config().threads, 1u);
  const std::vector<std::uint64_t> before(h.table().begin(), h.table().end());
  h.set_threads(4);
  EXPECT_EQ(h.config().threads, 4u);
  EXPECT_EQ(std::vector<std::uint64_t>(h.table().begin(), h.table().end()), before);  // the table unchanged
  std::vector<std::uint32_t> got(keys.size());
  std::vector<std::uint8_t> found(keys.size());
  EXPECT_EQ(h.find(keys, got, found), keys.size());
  EXPECT_EQ(got, values_of(keys));
}

// memory_for is what a table of that extent holds, so a caller can check
// it against the machine before the table is made.
TEST(SpatialHash, MemoryForIsTheMemoryOfTheTableItSizes) {
  for (const Extent t : {Extent{1, 1}, Extent{7, 9}, Extent{100, 37}}) {
    SpatialHash h(fixed({100, 100}));
    h.rehash(t);
    EXPECT_EQ(SpatialHash::memory_for(h.config(), t), h.memory_bytes()) << t.str();
  }
  // 2^62 slots of 8 bytes: saturated, not wrapped to a small number
  EXPECT_EQ(SpatialHash::memory_for(fixed({1u << 31, 1u << 31}), {1u << 31, 1u << 31}), UINT64_MAX);
}

TEST(SpatialHash, StatsCountAgesAndMemoryAndMissesStopEarly) {
  const Domain d{1024, 1024};
  const auto [keys, absent] = random_keys(d, 100000, 10000, 21);
  SpatialHash h(fixed(d));
  h.reserve(keys.size(), 0.8);
  h.insert(keys);
  const SpatialHashStats s = h.stats();
  EXPECT_EQ(std::accumulate(s.ages.begin(), s.ages.end(), std::uint64_t{0}), keys.size());
  EXPECT_GE(s.mean_age, 1.0);
  EXPECT_LT(s.mean_age, 4.0);
  EXPECT_GE(s.max_age, 2u);
  EXPECT_EQ(s.memory_bytes, h.memory_bytes());
  EXPECT_NEAR(s.bytes_per_key, 10.0 / 0.8, 0.5);  // a slot's 8 bytes and the miss filter's 2
  double probes = 0;
  for (const Key& k : absent) probes += h.probes(k);
  EXPECT_LT(probes / static_cast<double>(absent.size()), static_cast<double>(s.max_age));
}

// The miss filter (issue 36) is derived state: a table with one and a table
// without hold the same slots and max-age cells and answer alike, before and
// after erases; with it most misses read no slot.
TEST(SpatialHash, TheMissFilterChangesNoSlotAndNoAnswerAndAnswersMostMissesWithoutReadingASlot) {
  for (const Domain d : {Domain{2048, 1024, 1}, Domain{96, 80, 64}}) {
    const auto [keys, absent] = random_keys(d, 60000, 60000, 11);
    const std::vector<std::uint32_t> values = values_of(keys);
    for (const auto& [load, bits] : {std::pair{0.5, 16u}, std::pair{0.95, 16u}, std::pair{0.99, 16u},
                                     std::pair{0.95, 8u}}) {
      SCOPED_TRACE(d.str() + " load " + std::to_string(load) + ", " + std::to_string(bits) + " bits");
      SpatialHashConfig with = fixed(d), without = fixed(d);
      with.miss_filter_bits = bits;
      without.miss_filter_bits = 0;
      SpatialHash a(with), b(without);
      a.reserve(keys.size(), load);
      b.reserve(keys.size(), load);
      a.insert(keys, values);
      b.insert(keys, values);
      ASSERT_TRUE(std::ranges::equal(a.table(), b.table()));
      EXPECT_TRUE(std::ranges::equal(a.max_age(), b.max_age()));
      EXPECT_TRUE(b.filter().empty());
      EXPECT_EQ(a.memory_bytes() - b.memory_bytes(), a.filter().size() * 4);
      std::vector<Key> queries = keys;
      queries.insert(queries.end(), absent.begin(), absent.end());
      for (const int round : {0, 1}) {
        std::vector<std::uint32_t> va(queries.size()), vb(queries.size());
        std::vector<std::uint8_t> fa(queries.size()), fb(queries.size());
        EXPECT_EQ(a.find(queries, va, fa), b.find(queries, vb, fb));
        EXPECT_EQ(va, vb) << "round " << round;
        EXPECT_EQ(fa, fb) << "round " << round;
        // Then every third key erased: tombstones keep their filter bits.
        const std::vector<Key> gone(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(keys.size() / 3));
        a.erase(gone);
        b.erase(gone);
      }
      std::uint64_t unread = 0;
      for (const Key& k : absent) unread += a.probes(k) == 0u;
      EXPECT_GT(static_cast<double>(unread) / static_cast<double>(absent.size()), bits == 16u ? 0.97 : 0.9);
    }
  }
}

// The filter's words are ors of the keys' bits: the same for every thread
// count and order, and made again from the records alike (restore,
// set_miss_filter). Keys whose records were pushed out keep their bits in
// the table that inserted them: the filter made from the records is then a
// subset, never a superset.
TEST(SpatialHash, TheMissFilterIsTheSameForEveryThreadCountAndOrderAndIsMadeAgainFromTheRecordsParallel) {
  const Domain d{512, 384, 1};
  auto [keys, unused] = random_keys(d, 50000, 0, 12);
  std::vector<std::uint32_t> reference;
  for (const std::uint32_t threads : {1u, 2u, 4u}) {
    SpatialHashConfig c = fixed(d, threads);
    c.rule = DuplicateRule::Max;
    SpatialHash h(c);
    h.reserve(keys.size(), 0.95);
    std::shuffle(keys.begin(), keys.end(), std::mt19937_64(threads));
    h.insert(keys);
    const std::vector<std::uint32_t> words(h.filter().begin(), h.filter().end());
    if (reference.empty()) reference = words;
    else EXPECT_TRUE(words == reference) << threads << " threads";
    const SpatialHash back = SpatialHash::restore(h.config(), h.table_extent(), {h.table().begin(), h.table().end()},
                                                  {h.max_age().begin(), h.max_age().end()});
    EXPECT_TRUE(std::ranges::equal(back.filter(), h.filter()));
    h.set_miss_filter(0);
    EXPECT_TRUE(h.filter().empty());
    EXPECT_EQ(h.find(keys[5]), 0u);
    h.set_miss_filter(8);
    EXPECT_EQ(h.filter().size(), std::uint64_t{(h.table_extent().x + 7) / 8} * ((h.table_extent().y + 7) / 8) * 16);
    EXPECT_EQ(h.find(keys[6]), 0u);
    h.set_miss_filter(16);
    EXPECT_TRUE(std::ranges::equal(h.filter(), reference));
    EXPECT_THROW(h.set_miss_filter(4), std::invalid_argument);
  }
  // Tombstones pushed out and lost keys (1 700 records for 1 600 slots, no growth):
  // their bits stay, the records' filter lacks them, the answers agree.
  SpatialHashConfig c = fixed({64, 64, 1}, 1);
  c.age_bits = 4;
  c.lossless = false;
  SpatialHash h(c);
  h.rehash({40, 40});
  const auto [first, second] = random_keys({64, 64, 1}, 1000, 700, 13);
  h.insert(first);
  h.erase(first);
  const InsertReport r = h.insert(second);
  ASSERT_GT(r.tombstones_dropped + r.lost, 0u);
  const SpatialHash back = SpatialHash::restore(h.config(), h.table_extent(), {h.table().begin(), h.table().end()},
                                                {h.max_age().begin(), h.max_age().end()});
  for (std::size_t w = 0; w < h.filter().size(); ++w) EXPECT_EQ(back.filter()[w] & ~h.filter()[w], 0u) << w;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) EXPECT_EQ(back.find({x, y, 0}), h.find({x, y, 0})) << x << ", " << y;
}

// Limit cases: sides not a multiple of the filter's 8, one slot, one row,
// max-age blocks of 1 and wider than the table, the fewest and most age
// bits; memory_for counts the filter.
TEST(SpatialHash, TheMissFilterCoversTablesOfEverySideBlockAndAgeBits) {
  for (const Extent t : {Extent{1, 1}, Extent{7, 9}, Extent{9, 17}, Extent{300, 1}, Extent{100, 37}})
    for (const std::uint32_t block : {1u, 8u, 512u})
      for (const std::uint32_t age_bits : {4u, 12u}) {
        SCOPED_TRACE(t.str() + " block " + std::to_string(block) + " age bits " + std::to_string(age_bits));
        SpatialHashConfig c = fixed({300, 300, 1}, 1);
        c.block = block;
        c.age_bits = age_bits;
        c.rule = DuplicateRule::Max;
        SpatialHash h(c);
        h.rehash(t);
        EXPECT_EQ(h.filter().size(), std::uint64_t{(t.x + 7) / 8} * ((t.y + 3) / 4) * 16);
        EXPECT_EQ(SpatialHash::memory_for(h.config(), t), h.memory_bytes());
        const std::size_t n = std::min<std::uint64_t>(t.area(), 300) * 3 / 4;
        const auto [keys, absent] = random_keys({300, 300, 1}, n, 2000, 14);
        h.insert(keys);  // lossless growth where the small table cannot hold them
        for (const Key& k : keys) ASSERT_TRUE(h.contains(k));
        for (const Key& k : absent) ASSERT_FALSE(h.contains(k));
        c.miss_filter_bits = 0;
        EXPECT_EQ(SpatialHash::memory_for(h.config(), h.table_extent()) -
                      SpatialHash::memory_for(c, h.table_extent()),
                  h.filter().size() * 4);
        h.set_miss_filter(8);
        EXPECT_EQ(h.filter().size(), std::uint64_t{(h.table_extent().x + 7) / 8} * ((h.table_extent().y + 7) / 8) * 16);
        EXPECT_EQ(SpatialHash::memory_for(h.config(), h.table_extent()), h.memory_bytes());
        for (const Key& k : keys) ASSERT_TRUE(h.contains(k));
        for (const Key& k : absent) ASSERT_FALSE(h.contains(k));
      }
}

}  // namespace
}  // namespace habuffer::spatial

namespace habuffer::spatial {
namespace {

// The key-stream experiment's simulator, written apart from the container,
// builds SpatialHash's table for the same keys and offsets.
TEST(KeyExperiment, TheSimulatorsCoherentRobinHoodTableIsTheSpatialHashs) {
  for (const Domain d : {Domain{300, 200, 1}, Domain{40, 30, 20}}) {
    const auto [keys, unused] = random_keys(d, d.z == 1 ? 40000 : 15000, 0, 4);
    SpatialHashConfig c = fixed(d, 1);
    c.rule = DuplicateRule::Max;
    SpatialHash h(c);
    h.reserve(keys.size(), 0.95);
    h.insert(keys);
    const std::vector<std::uint64_t> sim =
        simulate_coherent_robin_hood(keys, d, h.table_extent(), c.age_bits, h.offsets());
    EXPECT_TRUE(std::equal(sim.begin(), sim.end(), h.table().begin(), h.table().end())) << d.str();
  }
}

// Robin Hood against first-come on the sparse image at load 0.95 (fixed
// seeds, 5 trials; the margins are over 5 times the 95 % half-widths seen):
// Robin Hood keeps the largest age and the reads of a miss far lower, while
// the mean age, the same sum of displacements, barely moves.
TEST(KeyExperiment, RobinHoodBoundsTheLargestAgeAndTheMissesThatFirstComeLetsGrow) {
  KeyExperimentConfig c;
  c.keys.set = KeySet::SparseImage;
  c.keys.domain = {192, 192, 1};
  c.loads = {0.95};
  c.trials = 5;
  c.probing = {KeyProbing::Coherent};
  c.misses = 3000;
  const std::vector<KeyExperimentRow> rows = run_key_experiment(c);
  ASSERT_EQ(rows.size(), 2u);
  const KeyExperimentRow& rh = rows[0];
  const KeyExperimentRow& fc = rows[1];
  EXPECT_EQ(rh.variant, "coherent/robinhood");
  EXPECT_EQ(fc.variant, "coherent/firstcome");
  EXPECT_LT(rh.mean_max_age * 4, fc.mean_max_age);
  EXPECT_LT(rh.miss_reads * 2, fc.miss_reads);
  EXPECT_NEAR(rh.mean_age, fc.mean_age, 0.5);
  EXPECT_EQ(rh.failures, 0.0);
  EXPECT_NEAR(rh.stored_load, 0.95, 0.01);
  c.loads = {1.5};
  EXPECT_THROW((void)run_key_experiment(c), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer::spatial
