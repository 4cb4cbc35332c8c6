// Pixel-ordered insertion into the HA-buffer on the CPU path (issue 26).
//
// SPEC 9 makes the final table (and max-age table) the same for every order
// of insertion when nothing fails and early cull is off. The CPU path may
// therefore pick the order that costs least: a frame bucketed by pixel, each
// pixel's records nearest first. Two things then come for free:
//
// - Exact duplicates sit next to each other after the sort and are counted
//   without a probe.
// - The "jump start": a pixel's next record starts one age past where its
//   previous (nearer, so larger) record was first written. Every slot the
//   previous record passed holds a larger word than it (it lost there), and
//   the slot where it was written holds at least it; slots only grow during
//   a gather, so each of those slots still beats the next, smaller record of
//   the same age: its atomicMax there would change nothing. Skipping those
//   probes (and counting them as iterations, so the iteration limit reads
//   the same) gives exactly the table writes of an insertion that made them.
//   docs/spec-notes.md, "Pixel-ordered insertion (issue 26)", has the proof.
//
// Probe steps per fragment fall from the sum of final ages to about one
// past the previous record's (measured: 8.8 to 2.8 on engine, 11.7 to 3.0
// on hairball). Threads own bands of rows holding about equal numbers of
// fragments; they still share the table through atomics (a band's probes
// reach other bands' slots at high ages), but rarely meet.
//
// With early cull the order is a different schedule (culls can only grow
// when the nearest come first); the jump start is not used, since the probes
// it skips are where a record meets the opacity in front of it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"
#include "habuffer/parallel.h"
#include "jump_start_lanes.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer::detail {

// Rows [y0, y1) of the screen.
struct RowBand {
  std::uint32_t y0 = 0, y1 = 0;
};

// At most `parts` bands of consecutive rows covering rows [0, per_row.size()),
// holding about equal numbers of records (per_row[y]: row y's; a band may
// be empty of rows when a few rows hold most of the records).
std::vector<RowBand> bands_from_rows(std::span<const std::uint64_t> per_row, std::uint32_t parts);

// The pixels the batch covers, counted in the on-screen check's pass (issue
// 36: Auto's rule reads fragments per covered pixel; a pass of its own cost
// more than it saved): throws as check_on_screen, naming the first fragment
// off the screen. `threads` slices, each marking a bitmap of its own in
// `bitmaps` (kept by the caller between calls).
std::uint64_t check_and_count_covered(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads,
                                      std::vector<std::vector<std::uint64_t>>& bitmaps);

// One band's fragments as age-1 records bucketed by pixel, each pixel's
// nearest first (records in decreasing order, identical ones adjacent). Kept
// by the buffer between calls, so a frame does not fault in fresh pages.
template <class Word>
class PixelBuckets {
 public:
  // The most fragments one fill takes (32-bit bucket offsets).
  static constexpr std::size_t kMaxFragments = UINT32_MAX;

  // `pack(fragment)` gives the fragment's age-1 record; fragments whose
  // depth `valid` refuses are counted in `invalid`, not bucketed. At most
  // kMaxFragments fragments.
  template <class Valid, class Pack>
  void fill(std::span<const Fragment> fragments, Extent screen, RowBand band, Valid valid, Pack pack,
            std::uint64_t& invalid) {
    origin_ = std::size_t{band.y0} * screen.x;
    width_ = screen.x;
    pixels_ = std::size_t{band.y1 - band.y0} * screen.x;
    // Counts at [i + 2], so that after the prefix sum end_[i + 1] is pixel
    // i's first record, and after the scatter (which advances it) its end.
    end_.assign(pixels_ + 2, 0);
    std::uint32_t n = 0;
    for (const Fragment& f : fragments)
      if (f.y >= band.y0 && f.y < band.y1) {
        if (valid(f)) {
          ++end_[local(f) + 2];
          ++n;
        } else {
          ++invalid;
        }
      }
    for (std::size_t i = 2; i < end_.size(); ++i) end_[i] += end_[i - 1];
    records_.resize(n);
    for (const Fragment& f : fragments)
      if (f.y >= band.y0 && f.y < band.y1 && valid(f)) records_[end_[local(f) + 1]++] = pack(f);
  }

  // The same from records staged for this band (stage_by_band): record i
  // belongs to the band's pixel pixels[i] (row-major from the band's first row).
  void fill_staged(std::span<const std::uint32_t> pixels, std::span<const Word> records, Extent screen, RowBand band) {
    origin_ = std::size_t{band.y0} * screen.x;
    width_ = screen.x;
    pixels_ = std::size_t{band.y1 - band.y0} * screen.x;
    end_.assign(pixels_ + 2, 0);
    for (const std::uint32_t p : pixels) ++end_[p + 2];
    for (std::size_t i = 2; i < end_.size(); ++i) end_[i] += end_[i - 1];
    records_.resize(records.size());
    for (std::size_t i = 0; i < records.size(); ++i) records_[end_[pixels[i] + 1]++] = records[i];
  }

  // Pixels of the band, row by row (indices for records()).
  [[nodiscard]] std::size_t pixels() const { return pixels_; }
  // Pixel i's records, sorted nearest first by this call (empty: none); `p`
  // is set to the pixel.
  std::span<const Word> records(std::size_t i, glm::uvec2& p) {
    const std::uint32_t begin = end_[i], end = end_[i + 1];
    if (begin == end) return {};
    const std::span<Word> list(records_.data() + begin, end - begin);
    nearest_first(list);
    const std::size_t pixel = origin_ + i;
    p = glm::uvec2(pixel % width_, pixel / width_);
    return list;
  }

 private:
  std::size_t local(const Fragment& f) const { return f.x + std::size_t{f.y} * width_ - origin_; }

  // Decreasing order: a pixel's list is short (tens of records), where an
  // insertion sort beats std::sort.
  static void nearest_first(std::span<Word> list) {
    if (list.size() > 32) {
      std::sort(list.begin(), list.end(), [](Word a, Word b) { return a > b; });
      return;
    }
    for (std::size_t i = 1; i < list.size(); ++i) {
      const Word w = list[i];
      std::size_t j = i;
      for (; j > 0 && list[j - 1] < w; --j) list[j] = list[j - 1];
      list[j] = w;
    }
  }

  std::size_t origin_ = 0, width_ = 1, pixels_ = 0;
  std::vector<std::uint32_t> end_;  // end_[i + 1]: the end of pixel i's records (end_[0] = end_[1] = 0)
  std::vector<Word> records_;
};

// One pixel's age-1 records (nearest first, identical ones adjacent)
// inserted with the jump start (early cull off), one probe step at a time, so
// that a thread may interleave several pixels (latency hiding) or run one to
// its end. On one thread this writes exactly what inserting the same records
// in the same order from age 1 writes, failures included
// (tests/test_insert_order.cpp).
template <class Kernel>
class JumpStartCursor {
 public:
  using Word = typename Kernel::ha_word;
  using Carry = typename Kernel::HabufferCarry;

  // Starts pixel p's records; `tally` receives each record's outcome.
  void begin(glm::uvec2 p, std::span<const Word> records) {
    p_ = p;
    next_ = records.data();
    end_ = records.data() + records.size();
    next_start_ = twin_start_ = 1;
    previous_ = 0;  // no record is 0 (ages start at 1)
    previous_failed_ = false;
  }

  // Moves to the next record that must probe, counting the duplicates on the
  // way; false when the pixel has no record left.
  bool next_record(Kernel& k, std::uint64_t* tally) {
    for (; next_ != end_; ++next_) {
      const Word r = *next_;
      // Its twin went before it and nothing was lost since: the twin is in
      // the table (perhaps moved further by an eviction): a duplicate.
      if (r == previous_ && !previous_failed_) {
        ++tally[HABUFFER_DUPLICATE];
        continue;
      }
      const std::uint32_t start = r == previous_ ? twin_start_ : next_start_;
      previous_ = r;
      ++next_;
      c_ = k.habuffer_carry_begin(p_, k.ha_code(r), k.ha_data(r));
      c_.a = start;
      c_.iter = start - 1;  // the skipped probes count, so the iteration limit reads the same
      if (start <= k.ha_max_age()) c_.r = k.ha_with_age(r, start);
      own_ = true;
      return true;
    }
    return false;
  }

  // The slot the next step probes, or nullptr when the record's call ends
  // without probing (for a prefetch).
  [[nodiscard]] const Word* next_slot(Kernel& k) const {
    if (k.ha_insert_limit(c_) != HABUFFER_PENDING) return nullptr;
    return k.slots() + k.ha_slot(k.ha_probe(c_.p, c_.a));
  }

  // One probe step of the current record's call; true when the call has
  // ended (its outcome tallied).
  bool step(Kernel& k, std::uint64_t* tally) {
    std::uint32_t outcome = k.ha_insert_limit(c_);
    if (outcome == HABUFFER_PENDING) {
      const std::uint32_t age = c_.a;
      outcome = k.ha_insert_step_at(c_, k.ha_probe(c_.p, c_.a), false);
      // The record was written at `age` (stored, or evicting a smaller
      // record: the carried one is then another pixel's, which may have its
      // very code and data), or its twin is there: a smaller record starts
      // one age further, a twin there.
      if (own_ && (outcome != HABUFFER_PENDING || c_.p != p_ || c_.r != k.ha_with_age(previous_, c_.a))) {
        own_ = false;
        next_start_ = age + 1;
        twin_start_ = age;
      }
      if (outcome == HABUFFER_PENDING) return false;
    }
    // The record itself failed: it lost at every age before c.a, so will the next.
    if (own_) next_start_ = twin_start_ = c_.a;
    previous_failed_ = outcome == HABUFFER_FAILED_AGE || outcome == HABUFFER_FAILED_ITER;
    ++tally[outcome];
    return true;
  }

 private:
  glm::uvec2 p_{0u};
  const Word* next_ = nullptr;
  const Word* end_ = nullptr;
  std::uint32_t next_start_ = 1;  // the age a smaller record starts at
  std::uint32_t twin_start_ = 1;  // the age an identical record starts at (it may meet its twin there)
  Word previous_ = 0;
  bool previous_failed_ = false;
  Carry c_{};
  bool own_ = false;  // still carrying the pixel's record (not one it evicted)
};

// Every pixel of `buckets` through the jump start, one after the other.
template <class Kernel, class Buckets>
void insert_pixels_jump_start(Kernel& k, Buckets& buckets, std::uint64_t* tally) {
  JumpStartCursor<Kernel> cursor;
  glm::uvec2 p;
  for (std::size_t i = 0; i < buckets.pixels(); ++i) {
    const auto records = buckets.records(i, p);
    if (records.empty()) continue;
    cursor.begin(p, records);
    while (cursor.next_record(k, tally))
      while (!cursor.step(k, tally)) {
      }
  }
}


// When a band interleaves its pixels: whenever the table exceeds this
// machine's L2 (cache_sizes.h). Measured with the specialised step
// (BM_InsertOrder and BM_HaSceneInsert, docs/performance.md, issue 36): 16
// lanes were as fast or faster than one pixel at a time on every stream
// beyond the L2, one record per pixel at load 0.5 included; within it they
// only add work. (Issue 26's shared-step lanes paid only for deep pixels or
// full tables above 8 MiB, which missed engine's 6.6 MiB table.)
struct InterleaveRule {
  std::optional<bool> forced;  // InsertOptions::interleave
  bool large_table = false;    // larger than the L2

  [[nodiscard]] bool applies() const { return forced ? *forced : large_table; }
};

// Every pixel of `buckets` through the jump start, kInterleavedPixels at a
// time: each lane makes one probe step, then prefetches the slot of its next
// step, so a slot's miss overlaps the other lanes' work. The steps of
// different pixels interleave as concurrent calls would (SPEC 9: the same
// table); a pixel's own records stay in order in its lane.
template <class Kernel, class Buckets>
void insert_pixels_interleaved(Kernel& k, Buckets& buckets, std::uint64_t* tally) {
  JumpStartCursor<Kernel> lanes[kInterleavedPixels];
  bool busy[kInterleavedPixels] = {};
  std::size_t next_pixel = 0, working = 0;
  glm::uvec2 p;
  // Gives lane l the next pixel with a record to probe; false when none is left.
  const auto refill = [&](std::size_t l) {
    for (; next_pixel < buckets.pixels(); ++next_pixel) {
      const auto records = buckets.records(next_pixel, p);
      if (records.empty()) continue;
      ++next_pixel;
      lanes[l].begin(p, records);
      if (lanes[l].next_record(k, tally)) return true;
    }
    return false;
  };
  const auto prefetch = [&](std::size_t l) {
    if (const auto* slot = lanes[l].next_slot(k)) __builtin_prefetch(slot, 1);
  };
  for (std::size_t l = 0; l < kInterleavedPixels; ++l)
    if ((busy[l] = refill(l))) {
      ++working;
      prefetch(l);
    }
  while (working > 0)
    for (std::size_t l = 0; l < kInterleavedPixels; ++l) {
      if (!busy[l]) continue;
      if (lanes[l].step(k, tally) && !lanes[l].next_record(k, tally) && !(busy[l] = refill(l))) {
        --working;
        continue;
      }
      prefetch(l);
    }
}

// Every pixel's records one by one, nearest first, each from age 1 (early
// cull on: the order changes what is culled, so no probe is skipped).
template <class Kernel, class Buckets>
void insert_pixels_in_order(Kernel& k, Buckets& buckets, std::uint64_t* tally) {
  glm::uvec2 p;
  for (std::size_t i = 0; i < buckets.pixels(); ++i)
    for (const auto r : buckets.records(i, p)) ++tally[k.ha_insert_code(p, k.ha_code(r), k.ha_data(r))];
}

// What pixel order keeps between calls (a frame then touches no fresh
// pages): one PixelBuckets per band, and the staging of the bucketing pass
// that several threads share.
template <class Word>
struct PixelOrderScratch {
  std::vector<PixelBuckets<Word>> buckets;
  std::vector<std::uint32_t> staged_pixels;  // each staged record's pixel within its band
  std::vector<Word> staged_records;
  std::vector<std::size_t> band_begin;       // band b's staged records: [band_begin[b], band_begin[b + 1])
  std::vector<std::vector<std::uint64_t>> row_counts;  // per thread, valid records per row of its slice
};

// One bucketing pass shared by `threads` threads (issue 36: each used to
// read the whole stream to pick out its band's fragments): each thread
// counts the valid records per row of its own slice of the stream; bands of
// rows are balanced by those records; each thread then scatters its slice's
// records to their bands (contiguous, in slice order), so a band's thread
// buckets its pixels from its own staged records alone. Returns the bands;
// `invalid[t]` counts slice t's fragments whose depth `valid` refuses.
// Runs inside run_with_threads(threads).
template <class Word, class Valid, class Pack>
std::vector<RowBand> stage_by_band(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads,
                                   Valid valid, Pack pack, PixelOrderScratch<Word>& s,
                                   std::vector<PartCount>& invalid) {
  const auto slice = [&](std::uint32_t t) {
    const std::size_t begin = fragments.size() * t / threads, end = fragments.size() * (t + 1) / threads;
    return fragments.subspan(begin, end - begin);
  };
  s.row_counts.resize(threads);
  invalid.assign(threads, {});
  fork_join(threads, [&](std::uint32_t t) {
    std::vector<std::uint64_t>& rows = s.row_counts[t];
    rows.assign(screen.y, 0);
    std::uint64_t bad = 0;
    for (const Fragment& f : slice(t)) {
      if (valid(f))
        ++rows[f.y];
      else
        ++bad;
    }
    invalid[t].n = bad;
  });
  std::vector<std::uint64_t> per_row(screen.y, 0);
  for (const auto& rows : s.row_counts)
    for (std::uint32_t y = 0; y < screen.y; ++y) per_row[y] += rows[y];
  std::vector<RowBand> bands = bands_from_rows(per_row, threads);
  std::vector<std::uint32_t> band_of_row(screen.y);
  for (std::uint32_t b = 0; b < bands.size(); ++b)
    for (std::uint32_t y = bands[b].y0; y < bands[b].y1; ++y) band_of_row[y] = b;
  // Thread t writes band b's records from cursor[t][b] on: bands in order,
  // threads in order within a band.
  std::vector<std::vector<std::size_t>> cursor(threads, std::vector<std::size_t>(bands.size()));
  s.band_begin.assign(bands.size() + 1, 0);
  std::size_t at = 0;
  for (std::uint32_t b = 0; b < bands.size(); ++b) {
    s.band_begin[b] = at;
    for (std::uint32_t t = 0; t < threads; ++t) {
      cursor[t][b] = at;
      for (std::uint32_t y = bands[b].y0; y < bands[b].y1; ++y) at += s.row_counts[t][y];
    }
  }
  s.band_begin[bands.size()] = at;
  s.staged_pixels.resize(at);
  s.staged_records.resize(at);
  fork_join(threads, [&](std::uint32_t t) {
    std::vector<std::size_t>& next = cursor[t];
    for (const Fragment& f : slice(t)) {
      if (!valid(f)) continue;
      const std::uint32_t b = band_of_row[f.y];
      const std::size_t i = next[b]++;
      s.staged_pixels[i] = static_cast<std::uint32_t>(f.x + std::size_t{f.y - bands[b].y0} * screen.x);
      s.staged_records[i] = pack(f);
    }
  });
  return bands;
}

// The whole batch in pixel order on `threads` threads, each owning a band of
// rows and one of `buckets` (resized to the bands; kept by the caller
// between calls); `make_kernel(concurrent)` as for_slices (atomics unless one
// thread inserts alone: `shared` says other calls may insert meanwhile).
// Batches beyond PixelBuckets::kMaxFragments go in consecutive parts.
template <class Word, class MakeKernel>
Counters insert_pixel_ordered(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads,
                              MakeKernel make_kernel, bool shared, const InterleaveRule& interleave,
                              InsertStep step, PixelOrderScratch<Word>& scratch) {
  if (fragments.size() > PixelBuckets<Word>::kMaxFragments) {
    const std::size_t half = fragments.size() / 2;
    Counters total =
        insert_pixel_ordered<Word>(fragments.first(half), screen, threads, make_kernel, shared, interleave, step,
                                   scratch);
    total +=
        insert_pixel_ordered<Word>(fragments.subspan(half), screen, threads, make_kernel, shared, interleave, step,
                                   scratch);
    return total;
  }
  threads = std::max(1u, std::min(threads, screen.y));
  auto pure = make_kernel(std::false_type{});  // packing only: reads no buffer
  const auto valid = [&](const Fragment& f) { return pure.ha_fragment_valid(f.depth, f.coverage); };
  const auto pack = [&](const Fragment& f) { return pure.ha_pack(1u, pure.ha_fragment_code(f.depth, f.coverage), f.rgba); };
  std::vector<RowBand> bands{RowBand{0, screen.y}};
  std::vector<SliceCounters> parts;
  std::vector<PartCount> invalid;
  auto& buckets = scratch.buckets;
  const auto run_band = [&](auto& k, std::uint32_t b) {
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    if (threads == 1) {
      buckets[b].fill(fragments, screen, bands[b], valid, pack, tally[HABUFFER_INVALID]);
    } else {
      const std::size_t begin = scratch.band_begin[b], n = scratch.band_begin[b + 1] - begin;
      buckets[b].fill_staged(std::span<const std::uint32_t>(scratch.staged_pixels).subspan(begin, n),
                             std::span<const Word>(scratch.staged_records).subspan(begin, n), screen, bands[b]);
    }
    using Kernel = std::remove_reference_t<decltype(k)>;
    const bool lanes = interleave.applies();
    if (k.habuffer_cull_tau > 0.0f)
      insert_pixels_in_order(k, buckets[b], tally);
    else if (step == InsertStep::Shared && lanes)
      insert_pixels_interleaved(k, buckets[b], tally);
    else if (step == InsertStep::Shared)
      insert_pixels_jump_start(k, buckets[b], tally);
    else if (lanes)
      JumpStartLanes<Kernel, kInterleavedPixels, true>::run(k, buckets[b], tally);
    else
      JumpStartLanes<Kernel, 1, false>::run(k, buckets[b], tally);
    parts[b].c.add_tally(tally);
  };
  if (threads == 1) {
    buckets.resize(std::max<std::size_t>(buckets.size(), 1));
    parts.resize(1);
    if (shared) {
      auto k = make_kernel(std::true_type{});
      run_band(k, 0);
    } else {
      run_band(pure, 0);
    }
  } else {
    run_with_threads(threads, [&] {
      bands = stage_by_band<Word>(fragments, screen, threads, valid, pack, scratch, invalid);
      if (buckets.size() < bands.size()) buckets.resize(bands.size());
      parts.resize(bands.size());
      fork_join(static_cast<std::uint32_t>(bands.size()), [&](std::uint32_t b) {
        auto k = make_kernel(std::true_type{});
        run_band(k, b);
      });
    });
  }
  Counters total;
  for (const auto& part : parts) total += part.c;
  std::uint64_t bad[HABUFFER_OUTCOME_COUNT] = {};
  for (const PartCount& p : invalid) bad[HABUFFER_INVALID] += p.n;
  total.add_tally(bad);
  return total;
}

}  // namespace habuffer::detail
