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
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"
#include "habuffer/parallel.h"
#include "technique_parallel.h"

namespace habuffer::detail {

// Rows [y0, y1) of the screen.
struct RowBand {
  std::uint32_t y0 = 0, y1 = 0;
};

// At most `parts` bands of consecutive rows covering the screen, holding
// about equal numbers of fragments (a band may be empty of rows when a few
// rows hold most of the fragments).
std::vector<RowBand> balanced_row_bands(std::span<const Fragment> fragments, Extent screen, std::uint32_t parts);

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

  // visit(pixel, records) for every pixel holding records, row by row; the
  // records are sorted nearest first just before the visit.
  template <class Visit>
  void for_each_pixel(Visit visit) {
    for (std::size_t i = 0; i < pixels_; ++i) {
      const std::uint32_t begin = end_[i], end = end_[i + 1];
      if (begin == end) continue;
      const std::span<Word> list(records_.data() + begin, end - begin);
      nearest_first(list);
      const std::size_t pixel = origin_ + i;
      visit(glm::uvec2(pixel % width_, pixel / width_), std::span<const Word>(list));
    }
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

// Inserts pixel p's age-1 records (nearest first, identical ones adjacent)
// with the jump start (early cull off), tallying each record's outcome. On
// one thread this writes exactly what inserting the same records in the same
// order from age 1 writes, failures included (tests/test_insert_order.cpp).
template <class Kernel>
void insert_pixel_jump_start(Kernel& k, glm::uvec2 p, std::span<const typename Kernel::ha_word> records,
                             std::uint64_t* tally) {
  using Word = typename Kernel::ha_word;
  std::uint32_t next_start = 1;  // the age a smaller record starts at
  std::uint32_t twin_start = 1;  // the age an identical record starts at (it may meet its twin there)
  Word previous = 0;             // no record is 0 (ages start at 1)
  bool previous_failed = false;
  for (const Word r : records) {
    // Its twin went before it and nothing was lost since: the twin is in the
    // table (perhaps moved further by an eviction), so this is a duplicate.
    if (r == previous && !previous_failed) {
      ++tally[HABUFFER_DUPLICATE];
      continue;
    }
    const std::uint32_t start = r == previous ? twin_start : next_start;
    previous = r;
    typename Kernel::HaCarry c = k.ha_carry_begin(p, k.ha_code(r), k.ha_data(r));
    c.a = start;
    c.iter = start - 1;  // the skipped probes count, so the iteration limit reads the same
    if (start <= k.ha_max_age()) c.r = k.ha_with_age(r, start);
    bool own = true;  // still carrying r (not a record r evicted)
    std::uint32_t outcome = HABUFFER_PENDING;
    while (outcome == HABUFFER_PENDING) {
      outcome = k.ha_insert_limit(c);
      if (outcome != HABUFFER_PENDING) break;
      const std::uint32_t age = c.a;
      outcome = k.ha_insert_step_at(c, k.ha_probe(c.p, c.a), false);
      // r was written at `age` (stored, or evicting a smaller record: the
      // carried one is then another pixel's, which may have r's very code and
      // data), or its twin is there: a smaller record starts one age
      // further, a twin there.
      if (own && (outcome != HABUFFER_PENDING || c.p != p || c.r != k.ha_with_age(r, c.a))) {
        own = false;
        next_start = age + 1;
        twin_start = age;
      }
    }
    // r itself failed: it lost at every age before c.a, so will the next.
    if (own) next_start = twin_start = c.a;
    previous_failed = outcome == HABUFFER_FAILED_AGE || outcome == HABUFFER_FAILED_ITER;
    ++tally[outcome];
  }
}

// Inserts pixel p's age-1 records one by one in the given order (early cull
// on: the order changes what is culled, the probes do not skip).
template <class Kernel>
void insert_pixel_in_order(Kernel& k, glm::uvec2 p, std::span<const typename Kernel::ha_word> records,
                           std::uint64_t* tally) {
  for (const auto r : records) ++tally[k.ha_insert_code(p, k.ha_code(r), k.ha_data(r))];
}

// The whole batch in pixel order on `threads` threads, each owning a band of
// rows and one of `buckets` (resized to the bands; kept by the caller
// between calls); `make_kernel(concurrent)` as for_slices (atomics unless one
// thread inserts alone: `shared` says other calls may insert meanwhile).
// Batches beyond PixelBuckets::kMaxFragments go in consecutive parts.
template <class Word, class MakeKernel>
Counters insert_pixel_ordered(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads,
                              MakeKernel make_kernel, bool shared, std::vector<PixelBuckets<Word>>& buckets) {
  if (fragments.size() > PixelBuckets<Word>::kMaxFragments) {
    const std::size_t half = fragments.size() / 2;
    Counters total = insert_pixel_ordered<Word>(fragments.first(half), screen, threads, make_kernel, shared, buckets);
    total += insert_pixel_ordered<Word>(fragments.subspan(half), screen, threads, make_kernel, shared, buckets);
    return total;
  }
  const std::vector<RowBand> bands = balanced_row_bands(fragments, screen, threads);
  if (buckets.size() < bands.size()) buckets.resize(bands.size());
  std::vector<SliceCounters> parts(bands.size());
  const auto run_band = [&](auto& k, std::uint32_t b) {
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    buckets[b].fill(
        fragments, screen, bands[b], [&](const Fragment& f) { return k.ha_depth_valid(f.depth); },
        [&](const Fragment& f) { return k.ha_pack(1u, k.ha_depth_code(f.depth), f.rgba); }, tally[HABUFFER_INVALID]);
    if (k.ha_cull_tau > 0.0f)
      buckets[b].for_each_pixel([&](glm::uvec2 p, std::span<const Word> r) { insert_pixel_in_order(k, p, r, tally); });
    else
      buckets[b].for_each_pixel([&](glm::uvec2 p, std::span<const Word> r) { insert_pixel_jump_start(k, p, r, tally); });
    parts[b].c.add_tally(tally);
  };
  if (bands.size() == 1 && !shared) {
    auto k = make_kernel(std::false_type{});
    run_band(k, 0);
  } else {
    run_with_threads(static_cast<std::uint32_t>(bands.size()), [&] {
      fork_join(static_cast<std::uint32_t>(bands.size()), [&](std::uint32_t b) {
        auto k = make_kernel(std::true_type{});
        run_band(k, b);
      });
    });
  }
  Counters total;
  for (const auto& part : parts) total += part.c;
  return total;
}

}  // namespace habuffer::detail
