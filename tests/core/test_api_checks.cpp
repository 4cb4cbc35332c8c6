// The C++ API checks its arguments (pixels, sizes, configurations, imported
// state) with one short message, and insert() calls may overlap on one
// container (insert_gate.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <barrier>
#include <chrono>
#include <string>
#include <string_view>
#include <thread>

#include "habuffer/techniques/blended/blended_image.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/lossless_build.h"
#include "test_support.h"

namespace habuffer {
namespace {

constexpr std::uint32_t kCallers = 8;

// `callers` threads call insert(slice, options) on `b` at once, each its own
// contiguous slice of `frags`; the sum of their counters.
Counters insert_from_threads(FragmentBuffer& b, std::span<const Fragment> frags, const InsertOptions& options,
                             std::uint32_t callers = kCallers) {
  std::vector<Counters> counts(callers);
  std::barrier start(callers);
  std::vector<std::thread> threads;
  for (std::uint32_t t = 0; t < callers; ++t)
    threads.emplace_back([&, t] {
      const std::size_t begin = frags.size() * t / callers, end = frags.size() * (t + 1) / callers;
      start.arrive_and_wait();
      counts[t] = b.insert(frags.subspan(begin, end - begin), options);
    });
  for (std::thread& t : threads) t.join();
  Counters total;
  for (const Counters& c : counts) total += c;
  return total;
}

// The case: 8 threads calling HaBuffer::insert() in the default mode
// lost records in 22-45 of 200 rounds while the counters claimed them stored.
TEST(ConcurrentCalls, ParallelDefaultInsertCallsOnOneHaBufferStoreEveryRecordTheCountersClaim) {
  const Extent screen{32, 32};
  const BufferConfig c = test::config(screen, {48, 48});
  for (std::uint64_t round = 0; round < 200; ++round) {
    const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 1600, round + 1);
    HaBuffer serial = test::make_buffer(c);
    const Counters expected = serial.insert(frags);
    ASSERT_EQ(expected.failures(), 0u);
    HaBuffer b = test::make_buffer(c);
    const Counters got = insert_from_threads(b, frags, InsertOptions{});
    ASSERT_EQ(got, expected) << "round " << round;
    ASSERT_EQ(b.count_stored(), got.stored()) << "round " << round;
    ASSERT_EQ(test::table_words(b), test::table_words(serial)) << "round " << round;  // SPEC 9
    ASSERT_EQ(b.max_age().ages(), serial.max_age().ages()) << "round " << round;
  }
}

// Every mode and insert_one, overlapping: each call keeps its own rule, and
// the table is the serial one. Each caller makes many small calls, so that
// calls of different modes overlap.
TEST(ConcurrentCalls, ParallelCallsInEveryModeAndInsertOneOverlapOnOneHaBuffer) {
  const Extent screen{48, 32};
  const BufferConfig c = test::config(screen, {80, 64});
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 4000, 5);
  HaBuffer serial = test::make_buffer(c);
  const Counters expected = serial.insert(frags);
  ASSERT_EQ(expected.failures(), 0u);
  for (std::uint64_t round = 0; round < 60; ++round) {
    HaBuffer b = test::make_buffer(c);
    std::vector<Counters> counts(kCallers);
    std::barrier start(kCallers);
    std::vector<std::thread> threads;
    for (std::uint32_t t = 0; t < kCallers; ++t)
      threads.emplace_back([&, t] {
        const std::size_t begin = frags.size() * t / kCallers, end = frags.size() * (t + 1) / kCallers;
        InsertOptions o;
        if (t % 4 == 1) o.mode = InsertMode::Serial;
        if (t % 4 == 2) {
          o.mode = InsertMode::OwnerComputes;
          o.threads = 2;
        }
        start.arrive_and_wait();
        for (std::size_t i = begin; i < end; i += 25) {
          const std::span<const Fragment> batch = std::span(frags).subspan(i, std::min<std::size_t>(25, end - i));
          if (t % 4 == 3)
            for (const Fragment& f : batch) counts[t].count(b.insert_one(f));
          else
            counts[t] += b.insert(batch, o);
        }
      });
    for (std::thread& t : threads) t.join();
    Counters total;
    for (const Counters& n : counts) total += n;
    ASSERT_EQ(total, expected) << "round " << round;
    ASSERT_EQ(test::table_words(b), test::table_words(serial)) << "round " << round;
  }
}

// Every other technique: overlapping calls run one after the other, so the
// lists are the serial ones and the counters add up.
TEST(ConcurrentCalls, ParallelDefaultInsertCallsOnEveryTechniqueStoreEveryRecord) {
  const Extent screen{20, 12};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 2400, 9);
  for (Technique t : all_techniques()) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = frags.size() * 4;  // room for every pool technique: paged lists ask a page of 4 nodes at most per fragment
    c.layers = test::depth_complexity(frags, screen);
    const auto serial = make_fragment_buffer(c, OffsetSource{});
    const Counters expected = serial->insert(frags);
    for (std::uint64_t round = 0; round < 25; ++round) {
      const auto b = make_fragment_buffer(c, OffsetSource{});
      const Counters got = insert_from_threads(*b, frags, InsertOptions{});
      ASSERT_EQ(got, expected) << "round " << round;
      ASSERT_EQ(b->count_stored(), got.stored()) << "round " << round;
      ASSERT_EQ(test::traversed_lists(*b), test::traversed_lists(*serial)) << "round " << round;
    }
  }
}

// InsertGate itself: a shared hold waits while the gate is held alone, and
// an alone hold waits for the shared holders. The waits are watched for a
// while (a thread that ran when it must not have is caught; one that was
// merely slow to start cannot fail the test).
TEST(InsertGate, ASharedHoldWaitsWhileTheGateIsHeldAloneAndAnAloneHoldForSharedHoldsParallel) {
  InsertGate gate;
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    std::atomic<bool> shared_taken{false}, alone_taken{false};
    std::thread sharer;
    {
      const auto alone = gate.alone();
      EXPECT_FALSE(gate.alone_if_free());
      sharer = std::thread([&] {
        const auto shared = gate.shared();
        shared_taken.store(true);
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      EXPECT_FALSE(shared_taken.load()) << "a shared hold was taken while the gate was held alone";
    }
    sharer.join();
    EXPECT_TRUE(shared_taken.load());
    std::thread loner;
    {
      const auto shared = gate.shared();
      const auto another = gate.shared();  // shared holds go together
      EXPECT_FALSE(gate.alone_if_free());
      loner = std::thread([&] {
        const auto alone = gate.alone();
        alone_taken.store(true);
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      EXPECT_FALSE(alone_taken.load()) << "an alone hold was taken while shared holds were held";
    }
    loner.join();
    EXPECT_TRUE(alone_taken.load());
    EXPECT_TRUE(gate.alone_if_free()) << "every hold released";
  }
}

// The records a call that runs alone adds to an HA-buffer (an insert) or
// takes from it (clear, reset, import_state): one fragment on every 16th
// pixel, row by row, on a table the size of the screen (a load of 1/16,
// no failure, so any order of insertion gives one table: SPEC 9).
constexpr std::size_t kSample = 16;
const Extent kGateScreen{2048, 1024};  // 16 MiB of slots: clear's pass takes a while

BufferConfig gate_config() { return test::config(kGateScreen, kGateScreen); }

std::vector<Fragment> gate_pool() {
  SplitMix64 rng(77);
  std::vector<Fragment> pool;
  for (std::uint32_t y = 0; y < kGateScreen.y; ++y)
    for (std::uint32_t x = y % 16; x < kGateScreen.x; x += 16)
      pool.push_back({x, y, static_cast<float>(rng.below(1u << 20)) * 0x1.0p-20f,
                      static_cast<std::uint32_t>(rng.next()) | 1u});
  return pool;
}

// Sample j of the pool: kSample fragments spread over the whole screen
// (pool[j], pool[j + n], ... for n samples), no two samples sharing one.
std::vector<Fragment> gate_sample(const std::vector<Fragment>& pool, std::size_t j) {
  const std::size_t samples = pool.size() / kSample;
  std::vector<Fragment> s;
  for (std::size_t i = 0; i < kSample; ++i) s.push_back(pool[j + i * samples]);
  return s;
}

// Another thread makes default insert calls of the pool's samples, one after
// the other, pausing between them, from before `alone` (a call that runs
// alone, run here) starts until after it ends; returns each call's counters,
// by sample. A call made while `alone` runs must wait for it (insert_gate.h):
// it then finds its whole sample in the table or none of it, counting all
// duplicates or all stored. One that ran beside `alone` would find the
// table half changed, its sample spread over the screen: part of each.
// Calls alternate between one thread (Auto then finds the gate taken and
// asks for a shared hold) and two (Auto's shared hold at once).
template <class Alone>
std::vector<Counters> default_inserts_around(HaBuffer& b, const std::vector<Fragment>& pool, Alone&& alone) {
  const std::size_t samples = pool.size() / kSample;
  std::vector<Counters> counts(samples);
  std::atomic<std::size_t> made{0};
  std::atomic<bool> done{false};
  std::thread caller([&] {
    for (std::size_t j = 0; j < samples && !done.load(); ++j) {
      InsertOptions o;  // the default mode
      o.threads = j % 2 == 0 ? 1 : 2;
      counts[j] = b.insert(gate_sample(pool, j), o);
      made.store(j + 1);
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
  });
  while (made.load() < 2) std::this_thread::yield();
  alone();
  done.store(true);
  caller.join();
  counts.resize(made.load());
  return counts;
}

// Each call found all its sample or none of it (see default_inserts_around);
// the samples of the calls that stored theirs.
std::vector<Fragment> expect_whole_samples(const std::vector<Counters>& calls, const std::vector<Fragment>& pool) {
  std::vector<Fragment> stored;
  for (std::size_t j = 0; j < calls.size(); ++j) {
    const Counters& c = calls[j];
    EXPECT_EQ(c.fragments, kSample);
    EXPECT_TRUE(c.stored() == kSample || c.duplicates == kSample)
        << "default insert call " << j << " ran beside the call that runs alone: " << c.stored()
        << " of its records stored, " << c.duplicates << " found already there";
    if (c.stored() == kSample) {
      const std::vector<Fragment> s = gate_sample(pool, j);
      stored.insert(stored.end(), s.begin(), s.end());
    }
  }
  return stored;
}

// `b` holds the table and max-age table of `fragments` inserted alone.
void expect_table_of(const HaBuffer& b, const std::vector<Fragment>& fragments) {
  HaBuffer reference = test::make_buffer(b.config());
  const Counters n = reference.insert(fragments);
  ASSERT_EQ(n.failures(), 0u);
  EXPECT_EQ(test::table_words(b), test::table_words(reference));
  EXPECT_EQ(b.max_age().ages(), reference.max_age().ages());
}

TEST(ConcurrentCalls, DefaultInsertsWaitForASerialInsertToFinishParallel) {
  const std::vector<Fragment> pool = gate_pool();
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    HaBuffer b = test::make_buffer(gate_config());
    InsertOptions serial;
    serial.mode = InsertMode::Serial;
    Counters n;
    const auto calls = default_inserts_around(b, pool, [&] { n = b.insert(pool, serial); });
    expect_whole_samples(calls, pool);
    EXPECT_EQ(n.fragments, pool.size());
    expect_table_of(b, pool);
  }
}

TEST(ConcurrentCalls, DefaultInsertsWaitForAnOwnerComputesInsertToFinishParallel) {
  const std::vector<Fragment> pool = gate_pool();
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    HaBuffer b = test::make_buffer(gate_config());
    InsertOptions owners;
    owners.mode = InsertMode::OwnerComputes;
    owners.threads = 2;
    const auto calls = default_inserts_around(b, pool, [&] { b.insert(pool, owners); });
    expect_whole_samples(calls, pool);
    expect_table_of(b, pool);
  }
}

TEST(ConcurrentCalls, DefaultInsertsWaitForClearAndResetToFinishParallel) {
  const std::vector<Fragment> pool = gate_pool();
  for (bool counting : {true, false})
    for (int round = 0; round < 3; ++round) {
      SCOPED_TRACE((counting ? "clear, round " : "reset, round ") + std::to_string(round));
      HaBuffer b = test::make_buffer(gate_config());
      b.insert(pool);
      std::uint64_t cleared = 0;
      const auto calls = default_inserts_around(b, pool, [&] {
        if (counting)
          cleared = b.clear();
        else
          b.reset();
      });
      const std::vector<Fragment> after = expect_whole_samples(calls, pool);
      if (counting) {
        EXPECT_EQ(cleared, pool.size()) << "the calls before clear found their samples there";
      }
      expect_table_of(b, after);
    }
}

TEST(ConcurrentCalls, DefaultInsertsWaitForImportStateToFinishParallel) {
  const std::vector<Fragment> pool = gate_pool();
  HaBuffer source = test::make_buffer(gate_config());
  source.insert(pool);
  const std::vector<std::uint64_t> words = test::table_words(source);
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    HaBuffer b = test::make_buffer(gate_config());
    const auto calls = default_inserts_around(b, pool, [&] { b.import_state(words, source.max_age().ages()); });
    expect_whole_samples(calls, pool);
    EXPECT_EQ(test::table_words(b), words);
    EXPECT_EQ(b.max_age().ages(), source.max_age().ages());
  }
}

// Runs `f`, expecting it to throw E with a message containing every one of `parts`.
template <class E, class F>
void expect_refused(F&& f, std::initializer_list<std::string_view> parts) {
  try {
    f();
    ADD_FAILURE() << "nothing thrown";
  } catch (const E& e) {
    for (std::string_view part : parts) EXPECT_NE(std::string_view(e.what()).find(part), std::string_view::npos) << e.what();
  }
}

TEST(ArgumentChecks, PerPixelCallsOfEveryContainerRefusePixelsOffTheScreenNamingPixelAndScreen) {
  const Extent screen{4, 4};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 60, 3);
  for (Technique t : all_techniques()) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);  // the HA-buffer's table = the screen
    c.pool_capacity = frags.size();
    c.layers = test::depth_complexity(frags, screen);
    const auto b = make_fragment_buffer(c, OffsetSource{});
    b->insert(frags);
    std::vector<ListEntry> list{{1, 2, 3}};
    for (const auto& pixel : {std::pair{4u, 0u}, std::pair{0u, 4u}, std::pair{UINT32_MAX, UINT32_MAX}}) {
      const std::uint32_t x = pixel.first, y = pixel.second;  // copies: clang before 16 cannot capture a structured binding
      expect_refused<std::out_of_range>([&] { b->list(x, y, list); },
                                        {"pixel (" + std::to_string(x) + "," + std::to_string(y) + ")", "screen 4x4"});
    }
    b->list(3, 3, list);  // the last pixel is on the screen
  }
  HaBuffer ha = test::make_buffer(test::config(screen, screen));
  expect_refused<std::out_of_range>([&] { (void)ha.composite(4, 0, glm::vec3(0.0f)); }, {"pixel (4,0)", "screen 4x4"});
  expect_refused<std::out_of_range>([&] { (void)ha.max_age().at(1, 0); }, {"cell (1,0)", "cells 1x1"});
  TechniqueConfig kc = test::technique_config(Technique::KBuffer, screen);
  kc.occupancy = true;
  const KBuffer kb(kc);
  expect_refused<std::out_of_range>([&] { (void)kb.occupancy_limit(0, 9); }, {"pixel (0,9)", "screen 4x4"});
}

TEST(ArgumentChecks, ScreensAndTablesWithAZeroSideAreRefusedBeforeAnyDivision) {
  for (const Extent zero : {Extent{0, 0}, Extent{0, 5}, Extent{5, 0}}) {
    SCOPED_TRACE(zero.str());
    expect_refused<std::invalid_argument>([&] { (void)OffsetSequence::random(zero, 255, 1); }, {zero.str(), "no slots"});
    expect_refused<std::invalid_argument>([&] { (void)OffsetSequence::farthest(zero, 255, 1); }, {zero.str(), "no slots"});
    expect_refused<std::invalid_argument>([&] { (void)OffsetSequence::from_list(zero, 255, {}); }, {zero.str(), "no slots"});
    expect_refused<std::invalid_argument>([&] { (void)MaxAgeTable(zero, 8); }, {zero.str(), "no pixels"});
    for (Technique t : all_techniques()) {
      TechniqueConfig c = test::technique_config(t, zero);
      c.buffer.table = {};
      c.pool_capacity = 10;
      expect_refused<std::invalid_argument>([&] { (void)make_fragment_buffer(c, OffsetSource{}); },
                                            {"screen size " + zero.str(), "empty"});
    }
  }
  // A table with one zero side is not the screen's size (0x0 is).
  for (const Extent table : {Extent{1000, 0}, Extent{0, 1000}}) {
    const BufferConfig c = test::config({8, 8}, table);
    expect_refused<std::invalid_argument>([&] { c.validate(); }, {"table " + table.str(), "zero side"});
    expect_refused<std::invalid_argument>([&] { (void)make_fragment_buffer(ha_technique_config(c), OffsetSource{}); },
                                          {"table " + table.str(), "zero side"});
  }
  EXPECT_EQ(test::config({8, 8}, {}).table_or_screen(), (Extent{8, 8}));
}

TEST(ArgumentChecks, AContainerBuiltFromAnotherTechniquesConfigurationIsRefused) {
  const Extent screen{8, 8};
  const auto config = [&](Technique t) {
    TechniqueConfig c = test::technique_config(t, screen);
    c.pool_capacity = 100;
    return c;
  };
  expect_refused<std::invalid_argument>([&] { FixedArrays a(config(Technique::Lists)); },
                                        {"technique arrays's container", "technique lists"});
  expect_refused<std::invalid_argument>([&] { LinkedLists l(config(Technique::Ha)); },
                                        {"technique lists's container", "technique ha"});
  expect_refused<std::invalid_argument>([&] { LinkedLists l(config(Technique::Arrays)); }, {"lists", "arrays"});
  expect_refused<std::invalid_argument>([&] { KBuffer k(config(Technique::Arrays)); }, {"kbuffer", "arrays"});
  expect_refused<std::invalid_argument>([&] { BlendedImage b(config(Technique::KBuffer)); }, {"kbuffer"});
  expect_refused<std::invalid_argument>([&] { BlendedImage b(config(Technique::Ha)); }, {"ha"});
  // Its own configuration builds.
  EXPECT_EQ(LinkedLists(config(Technique::SortedLists)).technique(), Technique::SortedLists);
  EXPECT_EQ(FixedArrays(config(Technique::Arrays)).technique(), Technique::Arrays);
}

// A table word that no insertion could have left there is refused, naming the
// slot, and the buffer keeps its state.
TEST(ArgumentChecks, AnHaBufferRefusesToImportRecordsThatCannotBeThere) {
  const Extent screen{6, 5};
  const BufferConfig c = test::config(screen, {9, 7}, Layout::L64, 8, 2);
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 40, 2);
  HaBuffer built = test::make_buffer(c);
  built.insert(frags);
  const std::vector<std::uint64_t> words = test::table_words(built);
  const std::vector<std::uint32_t> ages = built.max_age().ages();
  HaBuffer b = test::make_buffer(c);
  b.import_state(words, ages);  // the real thing imports
  EXPECT_EQ(test::table_words(b), words);
  EXPECT_EQ(test::traversed_lists(b), test::traversed_lists(built));

  const RecordLayout layout = c.record_layout();
  const auto slot_of = [&](glm::uvec2 p, std::uint32_t a) {
    const glm::uvec2 o = b.offsets().values()[a - 1];
    return ((p.x + o.x) % 9) + std::uint64_t{(p.y + o.y) % 7} * 9;
  };
  const auto refused = [&](std::vector<std::uint64_t> t, std::vector<std::uint32_t> m,
                           std::initializer_list<std::string_view> parts) {
    expect_refused<std::invalid_argument>([&] { b.import_state(t, m); }, parts);
    EXPECT_EQ(test::table_words(b), words);  // unchanged
  };
  // A record of age 0.
  std::vector<std::uint64_t> t = words;
  const std::uint64_t empty = static_cast<std::uint64_t>(std::find(t.begin(), t.end(), 0u) - t.begin());
  t[empty] = layout.pack(0, 5, 7);
  refused(t, ages, {"slot " + std::to_string(empty), "age 0"});
  // A record whose age makes it a pixel off the screen: table slot (8, 6) at age 1 belongs to (8, 6) - O[0].
  t = words;
  std::uint32_t a = 1;
  glm::uvec2 owner;
  for (;; ++a) {
    const glm::uvec2 o = b.offsets().values()[a - 1];
    owner = glm::uvec2((8 + 9 - o.x) % 9, (6 + 7 - o.y) % 7);
    if (owner.x >= screen.x || owner.y >= screen.y) break;
  }
  t[8 + 6 * 9] = layout.pack(a, 5, 7);
  refused(t, ages, {"slot 62", "pixel (" + std::to_string(owner.x) + "," + std::to_string(owner.y) + ")", "screen 6x5"});
  // A record beyond its pixel's max-age cell: traversal would never reach it.
  t = words;
  const std::uint32_t cell_age = ages[built.max_age().cell_index(5, 4)];
  t[slot_of({5, 4}, cell_age + 1)] = layout.pack(cell_age + 1, 5, 7);
  refused(t, ages, {"pixel (5,4)", "max-age cell's " + std::to_string(cell_age)});
  // A max-age cell above AMAX.
  std::vector<std::uint32_t> m = ages;
  m[2] = 256;
  refused(words, m, {"cell (2,0)", "age 256", "AMAX 255"});
}

// The other containers' read-backs: lists whose links reach a node twice (a
// cycle would never end a walk), unsorted or merged-less lists, entries
// beyond the layout, k-buffer layers no insertion leaves.
TEST(ArgumentChecks, ListsArraysAndKBuffersRefuseToImportStateThatCannotBeThere) {
  const Extent screen{2, 1};
  const RecordLayout layout(Layout::L64, 8);
  TechniqueConfig lc = test::technique_config(Technique::Lists, screen);
  lc.pool_capacity = 3;
  LinkedLists lists(lc);
  const std::vector<glm::uvec2> entries{{900, 5}, {700, 5}, {800, 5}};
  lists.import_state(std::vector<std::uint32_t>{1, 3}, entries, std::vector<std::uint32_t>{2, 0, 0}, 3);  // (0,0): 900, 700
  std::vector<ListEntry> list;
  lists.list(0, 0, list);
  EXPECT_EQ(list.size(), 2u);
  expect_refused<std::invalid_argument>(
      [&] { lists.import_state(std::vector<std::uint32_t>{1, 0}, entries, std::vector<std::uint32_t>{2, 1, 0}, 3); },
      {"node 1 twice", "pixel (0,0)"});
  expect_refused<std::invalid_argument>(
      [&] { lists.import_state(std::vector<std::uint32_t>{2, 0}, entries, std::vector<std::uint32_t>{0, 3, 0}, 3); },
      {"entry 1 of pixel (0,0)", "not behind"});
  lists.list(0, 0, list);
  EXPECT_EQ(list.size(), 2u);  // unchanged by the refusals

  TechniqueConfig ac = test::technique_config(Technique::Arrays, screen);
  ac.layers = 2;
  FixedArrays arrays(ac);
  expect_refused<std::invalid_argument>(
      [&] { arrays.import_state(std::vector<std::uint32_t>{0, 2}, std::vector<glm::uvec2>{{0, 0}, {5, 1}, {0, 0}, {6, 1}}, 0); },
      {"entry 1 of pixel (1,0)", "not behind"});
  expect_refused<std::invalid_argument>(
      [&] { arrays.import_state(std::vector<std::uint32_t>{1, 0}, std::vector<glm::uvec2>{{1u << 24, 1}, {0, 0}, {0, 0}, {0, 0}}, 0); },
      {"entry 0 of pixel (0,0)", "depth code 16777216", "16777215"});

  TechniqueConfig kc = test::technique_config(Technique::KBuffer, screen);
  kc.layers = 2;
  KBuffer kb(kc);
  const auto words = [](std::vector<std::uint64_t> records) {
    std::vector<std::uint32_t> w;
    for (std::uint64_t r : records) {
      w.push_back(static_cast<std::uint32_t>(r));
      w.push_back(static_cast<std::uint32_t>(r >> 32));
    }
    return w;
  };
  kb.import_state(words({layout.pack(1, 9, 1), 0, layout.pack(1, 8, 1), 0}), {});
  expect_refused<std::invalid_argument>([&] { kb.import_state(words({layout.pack(2, 9, 1), 0, 0, 0}), {}); },
                                        {"layer 0 of pixel (0,0)", "age 2"});
  expect_refused<std::invalid_argument>([&] { kb.import_state(words({0, 0, 0, layout.pack(1, 9, 1)}), {}); },
                                        {"layer 1 of pixel (1,0)", "after an empty layer"});
  kb.list(0, 0, list);
  EXPECT_EQ(list, (std::vector<ListEntry>{{0, 9, 1}, {0, 8, 1}}));
}

}  // namespace
}  // namespace habuffer
