// Pixel-ordered insertion (issue 26, techniques/ha/cpu/src/pixel_order.h): the HA-buffer's CPU
// path may bucket a batch by pixel, nearest first, and start each record one
// age past where its pixel's previous record was first written. SPEC 9 says
// the table cannot tell: these tests hold it to that, and to honest counts
// where SPEC 9 no longer promises identity (failures, early cull).
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "pixel_order.h"  // the thread partition (core's private header, through the include path)
#include "test_support.h"

namespace habuffer {
namespace {

struct OrderCase {
  Extent screen;
  Extent table;
  Layout layout;
  std::uint32_t age_bits;
  std::uint32_t block;
  StreamKind kind;
  double load;
};

std::string describe(const OrderCase& c, std::uint64_t seed) {
  return "screen " + c.screen.str() + " table " + c.table.str() + " " + to_string(c.layout) +
         " A=" + std::to_string(c.age_bits) + " B=" + std::to_string(c.block) + " " + to_string(c.kind) + " load " +
         std::to_string(c.load) + " seed " + std::to_string(seed);
}

const std::vector<OrderCase> kCases{
    {{64, 48}, {64, 48}, Layout::L64, 8, 8, StreamKind::Coherent, 0.5},
    {{64, 48}, {64, 48}, Layout::L32, 8, 8, StreamKind::Random, 0.8},
    {{50, 70}, {75, 105}, Layout::L64, 6, 3, StreamKind::Coherent, 0.9},
    {{33, 17}, {66, 34}, Layout::L32, 5, 1, StreamKind::Random, 0.6},
    {{128, 128}, {128, 128}, Layout::L64, 8, 8, StreamKind::Coherent, 0.95},
    {{1, 40}, {1, 40}, Layout::L64, 8, 2, StreamKind::Random, 0.7},
    {{40, 1}, {52, 2}, Layout::L32, 12, 8, StreamKind::Random, 0.7},
};

// The case's stream with exact duplicates (some of them far apart, so arrival
// order meets them late), invalid depths and a depth-1 pixel.
std::vector<Fragment> stream_of(const OrderCase& c, std::uint64_t seed) {
  const auto n = static_cast<std::uint64_t>(c.load * static_cast<double>(c.table.area()));
  auto f = test::stream(c.screen, c.kind, n, seed);
  for (std::size_t i = 0; i + 7 < f.size(); i += 97) f[i + 3] = f[i];
  for (std::size_t i = 0; i + 1 < f.size() / 2; i += 211) f[f.size() - 1 - i] = f[i];
  if (!f.empty()) f[f.size() / 2].depth = std::numeric_limits<float>::quiet_NaN();
  if (f.size() > 2) f[1].depth = 1.5f;
  return f;
}

InsertOptions ordered(InsertOrder order, std::uint32_t threads = 1, InsertStep step = InsertStep::Specialised) {
  InsertOptions o;
  o.order = order;
  o.threads = threads;
  o.step = step;
  return o;
}

// The jump start's two probe steps: the specialised one (the default) and
// the shared GLSL step it must equal (techniques/ha/cpu/src/jump_start_lanes.h).
const InsertStep kSteps[] = {InsertStep::Specialised, InsertStep::Shared};

std::string to_text(InsertStep step) { return step == InsertStep::Shared ? "shared step" : "specialised step"; }

// Pixel order, arrival order's stream sorted by pixel, nearest first.
std::vector<Fragment> sorted_by_pixel(std::vector<Fragment> f, const RecordLayout& layout) {
  std::stable_sort(f.begin(), f.end(), [&](const Fragment& a, const Fragment& b) {
    if (a.y != b.y) return a.y < b.y;
    if (a.x != b.x) return a.x < b.x;
    const std::uint64_t ka = (std::uint64_t{layout.depth_code(a.depth)} << 32) | (layout.has_data() ? a.rgba : 0u);
    const std::uint64_t kb = (std::uint64_t{layout.depth_code(b.depth)} << 32) | (layout.has_data() ? b.rgba : 0u);
    return ka > kb;
  });
  return f;
}

TEST(InsertOrder, PixelOrderGivesArrivalOrdersTableMaxAgeAndCountersAtOneAndManyThreads) {
  for (const OrderCase& c : kCases)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE(describe(c, seed));
      const BufferConfig cfg = test::config(c.screen, c.table, c.layout, c.age_bits, c.block);
      const auto f = test::shuffled(stream_of(c, seed), seed * 7);
      HaBuffer arrival = test::make_buffer(cfg, seed);
      const Counters na = arrival.insert(f, ordered(InsertOrder::Arrival));
      ASSERT_EQ(na.failures(), 0u) << "the case must not fail: SPEC 9 promises identity only then";
      for (std::uint32_t threads : {1u, 2u, 3u})
        for (bool interleave : {false, true})
          for (InsertStep step : kSteps) {
          SCOPED_TRACE("threads " + std::to_string(threads) + (interleave ? " interleaved " : " ") + to_text(step));
          HaBuffer pixel = test::make_buffer(cfg, seed);
          InsertOptions o = ordered(InsertOrder::Pixel, threads, step);
          o.interleave = interleave;
          const Counters np = pixel.insert(f, o);
          EXPECT_EQ(test::table_words(pixel), test::table_words(arrival));
          EXPECT_EQ(pixel.max_age().ages(), arrival.max_age().ages());
          EXPECT_EQ(np, na);
        }
    }
}

// Planes over the whole screen: every pixel holds records with the very code
// and data of its neighbours', so a record evicted by another pixel's may
// look exactly like the one that evicted it, but for its pixel.
TEST(InsertOrder, PixelOrderEqualsArrivalOrderWhenNeighboursHoldIdenticalRecords) {
  const Extent screen{19, 13};
  for (Layout layout : {Layout::L32, Layout::L64})
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SCOPED_TRACE(to_string(layout) + " seed " + std::to_string(seed));
      std::vector<Fragment> f;
      for (int plane = 0; plane < 5; ++plane)
        for (std::uint32_t y = 0; y < screen.y; ++y)
          for (std::uint32_t x = 0; x < screen.x; ++x)
            if ((x * 7 + y * 3 + static_cast<std::uint32_t>(plane) + seed) % 4 != 0)
              f.push_back({x, y, 0.1f + 0.15f * static_cast<float>(plane), 0x80808080u});
      const BufferConfig cfg = test::config(screen, {38, 30}, layout, 6);  // load about 0.8
      HaBuffer arrival = test::make_buffer(cfg, seed);
      const Counters na = arrival.insert(test::shuffled(f, seed), ordered(InsertOrder::Arrival));
      ASSERT_EQ(na.failures(), 0u);
      for (bool interleave : {false, true})
        for (InsertStep step : kSteps) {
        SCOPED_TRACE(to_text(step));
        HaBuffer pixel = test::make_buffer(cfg, seed);
        InsertOptions o = ordered(InsertOrder::Pixel, 1, step);
        o.interleave = interleave;
        const Counters np = pixel.insert(f, o);
        EXPECT_EQ(np, na);
        EXPECT_EQ(test::table_words(pixel), test::table_words(arrival));
      }
    }
}

TEST(InsertOrder, PixelOrderEqualsArrivalOrderIntoABufferHoldingAnEarlierBatch) {
  const Extent screen{48, 40};
  const BufferConfig cfg = test::config(screen, {56, 48});
  const auto first = test::stream(screen, StreamKind::Coherent, 1200, 3);
  auto second = test::stream(screen, StreamKind::Coherent, 1200, 4);
  second.insert(second.end(), first.begin(), first.begin() + 300);  // duplicates of records already stored
  for (InsertStep step : kSteps) {
    SCOPED_TRACE(to_text(step));
    HaBuffer arrival = test::make_buffer(cfg), pixel = test::make_buffer(cfg);
    arrival.insert(first, ordered(InsertOrder::Arrival));
    pixel.insert(first, ordered(InsertOrder::Pixel, 1, step));
    const Counters na = arrival.insert(second, ordered(InsertOrder::Arrival));
    const Counters np = pixel.insert(second, ordered(InsertOrder::Pixel, 2, step));
    ASSERT_EQ(na.failures(), 0u);
    EXPECT_EQ(na.duplicates, 300u);
    EXPECT_EQ(np, na);
    EXPECT_EQ(test::table_words(pixel), test::table_words(arrival));
    EXPECT_EQ(pixel.max_age().ages(), arrival.max_age().ages());
  }
}

// The jump start only skips probes that would change nothing: on one thread
// it writes what the same records inserted in the same order from age 1 write,
// failures (age and iteration limits) and their counts included.
TEST(InsertOrder, JumpStartWritesWhatTheSameOrderFromAgeOneWritesEvenWhenInsertsFail) {
  for (std::uint32_t iter_limit : {HABUFFER_DEFAULT_ITER_LIMIT, 6u})
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SCOPED_TRACE("iteration limit " + std::to_string(iter_limit) + " seed " + std::to_string(seed));
      const Extent screen{24, 20};
      BufferConfig cfg = test::config(screen, screen, Layout::L64, 4);  // AMAX 15
      cfg.iter_limit = iter_limit;
      auto f = test::stream(screen, StreamKind::Coherent, 420, seed);  // load near 0.9
      for (int i = 0; i < 24; ++i) f.push_back({5, 7, 0.01f * static_cast<float>(i), 0x336699ffu});  // deeper than AMAX
      for (int i = 0; i < 6; ++i) f.push_back(f[static_cast<std::size_t>(i) * 61]);               // duplicates
      f.push_back(f[f.size() - 20]);  // the twin of a record on the deep pixel
      HaBuffer from_age_one = test::make_buffer(cfg, seed);
      const Counters n1 = from_age_one.insert(sorted_by_pixel(f, cfg.record_layout()), ordered(InsertOrder::Arrival));
      EXPECT_GT(n1.failures(), 0u) << "the case must fail somewhere";
      for (InsertStep step : kSteps) {
        SCOPED_TRACE(to_text(step));
        HaBuffer jumped = test::make_buffer(cfg, seed);
        InsertOptions o = ordered(InsertOrder::Pixel, 1, step);
        o.interleave = false;  // one pixel at a time: interleaving is another order, which failures tell apart
        const Counters n2 = jumped.insert(test::shuffled(f, seed), o);
        EXPECT_EQ(n2, n1);
        EXPECT_EQ(test::table_words(jumped), test::table_words(from_age_one));
        EXPECT_EQ(jumped.max_age().ages(), from_age_one.max_age().ages());
      }
    }
}

// Neighbouring pixels hold identical records (one code and data per plane)
// at every age up to AMAX and one past it, each fragment twice: on this full
// table many inserts write their record and then fail (the record they
// evicted finds no room, or the iteration limit ends the call). The twin that
// follows such an insert starts at the age where its record was written and
// meets it there, a duplicate, as the same records inserted from age one do;
// one starting a probe later would pass it and store the record twice.
TEST(InsertOrder, ATwinAfterAFailedInsertStartsWhereItsRecordWasWrittenAsFromAgeOne) {
  const Extent screen{13, 11};
  std::uint64_t failures = 0, duplicates = 0;
  for (Layout layout : {Layout::L32, Layout::L64})
    for (std::uint32_t iter_limit : {HABUFFER_DEFAULT_ITER_LIMIT, 5u, 9u})
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE(to_string(layout) + " iteration limit " + std::to_string(iter_limit) + " seed " +
                     std::to_string(seed));
        BufferConfig cfg = test::config(screen, {16, 12}, layout, 4);  // AMAX 15
        cfg.iter_limit = iter_limit;
        const std::uint32_t amax = cfg.record_layout().max_age();
        std::vector<Fragment> f;
        for (std::uint32_t plane = 0; plane <= amax; ++plane)
          for (std::uint32_t y = 0; y < screen.y; ++y)
            for (std::uint32_t x = 0; x < screen.x; ++x)
              if ((x * 5 + y * 3 + plane + static_cast<std::uint32_t>(seed)) % (seed + 1) != 0) {
                const Fragment one{x, y, 0.02f + 0.05f * static_cast<float>(plane), 0x4080c0ffu};
                f.push_back(one);
                f.push_back(one);  // its twin
              }
        HaBuffer from_age_one = test::make_buffer(cfg, seed);
        const Counters n1 = from_age_one.insert(sorted_by_pixel(f, cfg.record_layout()), ordered(InsertOrder::Arrival));
        failures += n1.failures();
        duplicates += n1.duplicates;
        // One pixel at a time: interleaved pixels are another order, which
        // failures can tell apart (pixel_order.h).
        for (InsertStep step : kSteps) {
          SCOPED_TRACE(to_text(step));
          HaBuffer jumped = test::make_buffer(cfg, seed);
          InsertOptions o = ordered(InsertOrder::Pixel, 1, step);
          o.interleave = false;
          const Counters n2 = jumped.insert(test::shuffled(f, seed), o);
          EXPECT_EQ(n2, n1);
          EXPECT_EQ(test::table_words(jumped), test::table_words(from_age_one));
          EXPECT_EQ(jumped.max_age().ages(), from_age_one.max_age().ages());
        }
      }
  EXPECT_GT(failures, 0u) << "the cases must fail somewhere";
  EXPECT_GT(duplicates, 0u);
}

// Where inserts fail SPEC 9 no longer promises one table; every fragment
// must still be counted once and every record counted stored be found.
TEST(InsertOrder, PixelOrderCountsEveryFragmentWhenAPixelIsDeeperThanAmaxAtManyThreads) {
  const Extent screen{16, 16};
  const BufferConfig cfg = test::config(screen, {20, 20}, Layout::L32, 4);  // AMAX 15
  std::vector<Fragment> f;
  for (int i = 0; i < 40; ++i) f.push_back({3, 3, 0.02f * static_cast<float>(i), 0});  // 40 records, AMAX 15
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) f.push_back({x, y, 0.5f, 0});  // depth 1 everywhere else
  for (std::uint32_t threads : {1u, 2u, 4u})
    for (InsertStep step : kSteps) {
    SCOPED_TRACE(to_text(step) + " threads " + std::to_string(threads));
    HaBuffer b = test::make_buffer(cfg);
    InsertOptions o = ordered(InsertOrder::Pixel, threads, step);
    o.interleave = threads != 2;
    const Counters n = b.insert(test::shuffled(f, threads), o);
    EXPECT_EQ(n.fragments, f.size());
    EXPECT_GT(n.failed_age, 0u);
    EXPECT_EQ(b.count_stored(), n.stored());
    EXPECT_EQ(test::traversed_lists(b).at({3, 3}).size() + n.failed_age + n.failed_iter, 41u)
        << "pixel (3,3): 40 records and one at depth 0.5, each stored or counted failed";
  }
}

TEST(InsertOrder, AutoChoosesPixelOrderForBatchesLargeAndDeepEnoughElseArrivalOrder) {
  const Extent screen{64, 64};
  const std::uint64_t enough = screen.area() / kPixelOrderPixelsPerFragment;
  const auto covering = [](std::uint64_t fragments, double depth) {
    return static_cast<std::uint64_t>(static_cast<double>(fragments) / depth);
  };
  InsertOptions o;
  EXPECT_EQ(choose_insert_order(o, enough, covering(enough, 4.0), screen), InsertOrder::Pixel);
  EXPECT_EQ(choose_insert_order(o, enough, covering(enough, kPixelOrderMinDepth), screen), InsertOrder::Pixel);
  EXPECT_EQ(choose_insert_order(o, enough, covering(enough, 3.0), screen), InsertOrder::Arrival)
      << "shallow pixels probe about once each in arrival order";
  EXPECT_EQ(choose_insert_order(o, enough - 1, covering(enough - 1, 8.0), screen), InsertOrder::Arrival);
  EXPECT_EQ(choose_insert_order(o, kPixelOrderMinFragments - 1, 1, {4, 4}), InsertOrder::Arrival);
  EXPECT_EQ(choose_insert_order(ordered(InsertOrder::Pixel), 1, 1, screen), InsertOrder::Pixel);
  EXPECT_EQ(choose_insert_order(ordered(InsertOrder::Arrival), enough, 1, screen), InsertOrder::Arrival);
  o.mode = InsertMode::OwnerComputes;
  EXPECT_EQ(choose_insert_order(o, enough, 1, screen), InsertOrder::Arrival);

  // The buffer counts the covered pixels in its on-screen check and says which order ran.
  std::vector<Fragment> deep, shallow;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) {
      shallow.push_back({x, y, 0.5f, 0x808080ffu});
      if (x < 16)
        for (int k = 0; k < 4; ++k) deep.push_back({x, y, 0.1f * static_cast<float>(k + 1), 0x808080ffu});
    }
  for (float tau : {0.0f, 0.9f}) {
    SCOPED_TRACE("early cull " + std::to_string(tau));
    BufferConfig cfg = test::config(screen, {96, 96});
    cfg.early_cull_tau = tau;
    for (std::uint32_t threads : {1u, 2u}) {
      HaBuffer b = test::make_buffer(cfg);
      EXPECT_EQ(b.insert_order(deep, ordered(InsertOrder::Auto, threads)), InsertOrder::Pixel);
      EXPECT_EQ(b.insert_order(shallow, ordered(InsertOrder::Auto, threads)), InsertOrder::Arrival);
      EXPECT_EQ(b.last_insert_order(), InsertOrder::Arrival) << "before any insert";
      b.insert(deep, ordered(InsertOrder::Auto, threads));
      EXPECT_EQ(b.last_insert_order(), InsertOrder::Pixel);
      b.insert(shallow, ordered(InsertOrder::Auto, threads));
      EXPECT_EQ(b.last_insert_order(), InsertOrder::Arrival);
    }
  }
  HaBuffer b = test::make_buffer(test::config(screen, screen));
  InsertOptions owner = ordered(InsertOrder::Pixel);
  owner.mode = InsertMode::OwnerComputes;
  EXPECT_THROW((void)b.insert_order(deep, owner), std::invalid_argument);
  EXPECT_THROW((void)b.insert(deep, owner), std::invalid_argument);
  auto off = deep;
  off[deep.size() / 2].x = screen.x;
  EXPECT_THROW((void)b.insert(off, InsertOptions{}), std::out_of_range) << "the counting pass checks the screen";
  EXPECT_THROW((void)b.insert(off, ordered(InsertOrder::Auto, 2)), std::out_of_range);
  EXPECT_EQ(b.count_stored(), 0u) << "nothing inserted before the check";
  EXPECT_EQ(parse_insert_order("pixel"), InsertOrder::Pixel);
  EXPECT_EQ(parse_insert_order("arrival"), InsertOrder::Arrival);
  EXPECT_EQ(parse_insert_order("auto"), InsertOrder::Auto);
  EXPECT_FALSE(parse_insert_order("sorted"));
}

// With early cull, nearest first is a different schedule of SPEC 6's rules:
// a record meets every nearer record of its pixel before it is placed, so it
// culls at least what arrival order culls on one thread, and never drops a
// fragment with opacity at most tau in front of it.
TEST(InsertOrder, PixelOrderUnderEarlyCullCullsAtLeastArrivalOrderAndKeepsTheBound) {
  const Extent screen{24, 24};
  for (float tau : {0.3f, 0.9f})
    for (std::uint64_t seed = 1; seed <= 4; ++seed)
      for (std::uint32_t threads : {1u, 2u}) {
        SCOPED_TRACE("tau " + std::to_string(tau) + " seed " + std::to_string(seed) + " threads " +
                     std::to_string(threads));
        BufferConfig cfg = test::config(screen, {96, 96});
        cfg.early_cull_tau = tau;
        const auto f = test::shuffled(test::grid_stream(screen, 4000, seed, 20), seed);
        HaBuffer arrival = test::make_buffer(cfg, seed), pixel = test::make_buffer(cfg, seed);
        const Counters na = arrival.insert(f, ordered(InsertOrder::Arrival));
        const Counters np = pixel.insert(f, ordered(InsertOrder::Pixel, threads));
        ASSERT_EQ(np.failures() + na.failures(), 0u);
        EXPECT_GE(np.culled, na.culled);
        EXPECT_EQ(pixel.count_stored(), np.stored());
        const auto kept = test::traversed_lists(pixel);
        for (const auto& [p, list] : test::exact_lists(f, pixel.record_layout())) {
          double acc = 0.0;
          const auto it = kept.find(p);
          for (const ListEntry& e : list) {
            if (acc > tau - 1e-6) break;
            ASSERT_TRUE(it != kept.end() && std::find(it->second.begin(), it->second.end(), e) != it->second.end())
                << "pixel (" << p.first << "," << p.second << ") lost a fragment with opacity " << acc << " in front";
            acc += (1.0 - acc) * ((e.data & 255u) / 255.0);
          }
        }
      }
}

// Several threads share one bucketing pass (issue 36): bands of rows hold
// about equal numbers of records, cover every row once, and each band's
// staged records are exactly its rows' valid fragments, in stream order.
TEST(InsertOrder, ThreadsShareOneBucketingPassIntoBandsBalancedByRecords) {
  SplitMix64 rng(11);
  for (int round = 0; round < 200; ++round) {
    const auto rows = static_cast<std::uint32_t>(1 + rng.below(40));
    const auto parts = static_cast<std::uint32_t>(1 + rng.below(6));
    std::vector<std::uint64_t> per_row(rows);
    std::uint64_t total = 0, widest = 0;
    for (auto& n : per_row) {
      n = rng.below(4) == 0 ? rng.below(1000) : rng.below(5);
      total += n;
      widest = std::max(widest, n);
    }
    const auto bands = detail::bands_from_rows(per_row, parts);
    const std::uint32_t usable = std::min(parts, rows);  // a band has a row at least
    ASSERT_LE(bands.size(), usable);
    std::uint32_t next = 0;
    for (const auto& band : bands) {
      ASSERT_EQ(band.y0, next) << "bands are consecutive";
      ASSERT_GE(band.y1, band.y0);
      next = band.y1;
      std::uint64_t held = 0;
      for (std::uint32_t y = band.y0; y < band.y1; ++y) held += per_row[y];
      EXPECT_LE(held, total / usable + widest + 1) << "a band holds its share and at most one row more";
    }
    EXPECT_EQ(next, rows) << "the bands cover every row";
  }

  const Extent screen{32, 24};
  auto f = test::stream(screen, StreamKind::Random, 3000, 5);
  for (std::size_t i = 0; i < f.size(); i += 37) f[i].depth = std::numeric_limits<float>::quiet_NaN();
  for (std::uint32_t threads : {2u, 3u, 5u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    detail::PixelOrderScratch<std::uint64_t> scratch;
    std::vector<detail::PartCount> invalid;
    const auto valid = [](const Fragment& g) { return g.depth == g.depth; };
    const auto pack = [&](const Fragment& g) { return std::uint64_t{g.x} << 40 | std::uint64_t{g.y} << 32 | g.rgba; };
    std::vector<detail::RowBand> bands;
    run_with_threads(threads, [&] {
      bands = detail::stage_by_band<std::uint64_t>(f, screen, threads, valid, pack, scratch, invalid);
    });
    std::uint64_t refused = 0;
    for (const auto& p : invalid) refused += p.n;
    EXPECT_EQ(refused, (f.size() + 36) / 37);
    for (std::size_t b = 0; b < bands.size(); ++b) {
      std::vector<std::uint64_t> want;
      for (const Fragment& g : f)
        if (valid(g) && g.y >= bands[b].y0 && g.y < bands[b].y1) want.push_back(pack(g));
      const std::size_t begin = scratch.band_begin[b], end = scratch.band_begin[b + 1];
      const std::vector<std::uint64_t> got(scratch.staged_records.begin() + static_cast<std::ptrdiff_t>(begin),
                                           scratch.staged_records.begin() + static_cast<std::ptrdiff_t>(end));
      EXPECT_EQ(got, want) << "band " << b;
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint64_t r = scratch.staged_records[i];
        const auto x = static_cast<std::uint32_t>(r >> 40), y = static_cast<std::uint32_t>((r >> 32) & 0xFF);
        ASSERT_EQ(scratch.staged_pixels[i], x + (y - bands[b].y0) * screen.x);
      }
    }
  }
}

}  // namespace
}  // namespace habuffer
