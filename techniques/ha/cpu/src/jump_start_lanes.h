// The jump start's probe loop specialised for the CPU (issue 36).
//
// Pixel order without early cull (pixel_order.h) inserts each pixel's
// records nearest first, each starting one age past where its predecessor
// was first written. JumpStartCursor runs that schedule through the shared
// GLSL step (ha_insert_step_at), the reference every path shares. This file
// runs the very same schedule with the step written out for the case it
// serves (early cull off, no saturation, one thread per pixel) and nothing
// else:
//
// - The slot of a lane's next probe is computed once, when the lane's age
//   changes, and kept: it is prefetched at once and loaded by the next step
//   (the cursor computed it twice, once to prefetch and once to probe).
// - A probe is one load: a slot at least as large as the carried record
//   loses (equal: a duplicate) with no atomic; a smaller one takes the
//   kernel's atomic max (a plain store on one thread), whose old value
//   decides as in the shared step (another thread may have raised the slot
//   between the load and the atomic).
// - "Still carrying the pixel's own record" is a flag cleared by the first
//   write: no record comparison per probe.
// - Lanes are kept as plain arrays of the few fields the cull-free step
//   reads (no opacity accumulator, no front record).
//
// Every table write, max-age raise, iteration count and outcome is the
// shared step's, in the same order per lane, so the table, the max-age table
// and the counters are identical (tests/test_insert_order.cpp runs every
// case through both steps; InsertStep::Shared selects the reference).
// Lanes > 1 interleaves that many pixels on one thread (AMAC-style latency
// hiding), prefetching each lane's next slot: different pixels' steps
// interleave as concurrent calls would (SPEC 9: the same table).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/vec2.hpp>

namespace habuffer::detail {

template <class Kernel, std::size_t Lanes, bool Prefetch>
class JumpStartLanes {
 public:
  using Word = typename Kernel::ha_word;

  // Inserts every pixel of `buckets` (PixelBuckets) through the jump start,
  // Lanes pixels at a time, tallying each call's outcome in `tally`.
  template <class Buckets>
  static void run(Kernel& k, Buckets& buckets, std::uint64_t* tally) {
    JumpStartLanes lanes(k, tally);
    lanes.insert_all(buckets);
  }

 private:
  struct Lane {
    Word r = 0;         // the carried record, with age a
    Word previous = 0;  // the pixel's last record (age 1), 0 before its first
    const Word* next = nullptr;  // the pixel's records not yet begun
    const Word* end = nullptr;
    std::uint64_t slot = 0;  // the slot of the next probe
    glm::uvec2 p{0u};        // the carried record's pixel
    glm::uvec2 pixel{0u};    // the lane's pixel
    std::uint32_t a = 1, iter = 0;
    std::uint32_t next_start = 1, twin_start = 1;  // as JumpStartCursor's
    bool own = false;              // still carrying the pixel's record
    bool previous_failed = false;  // the pixel's last call failed
  };

  JumpStartLanes(Kernel& k, std::uint64_t* tally)
      : k_(k), tally_(tally), max_age_(k.ha_max_age()), iter_limit_(k.habuffer_iter_limit) {}

  template <class Buckets>
  void insert_all(Buckets& buckets) {
    std::size_t next_pixel = 0, working = 0;
    std::array<bool, Lanes> busy{};
    // Gives lane l the next pixel with a record to probe; false when none is left.
    const auto refill = [&](Lane& lane) {
      glm::uvec2 p;
      while (next_pixel < buckets.pixels()) {
        const auto records = buckets.records(next_pixel++, p);
        if (records.empty()) continue;
        begin_pixel(lane, p, records.data(), records.data() + records.size());
        if (next_record(lane)) return true;
      }
      return false;
    };
    for (std::size_t l = 0; l < Lanes; ++l)
      if ((busy[l] = refill(lanes_[l]))) ++working;
    while (working > 0)
      for (std::size_t l = 0; l < Lanes; ++l) {
        if (!busy[l]) continue;
        Lane& lane = lanes_[l];
        if (step(lane) && !next_record(lane) && !(busy[l] = refill(lane))) --working;
      }
  }

  static void begin_pixel(Lane& lane, glm::uvec2 p, const Word* begin, const Word* end) {
    lane.pixel = p;
    lane.next = begin;
    lane.end = end;
    lane.next_start = lane.twin_start = 1;
    lane.previous = 0;
    lane.previous_failed = false;
  }

  // Starts the lane's next record that must probe, counting duplicates and
  // records that fail before probing; false when the pixel has none left.
  bool next_record(Lane& lane) {
    while (lane.next != lane.end) {
      const Word r = *lane.next++;
      if (r == lane.previous && !lane.previous_failed) {
        ++tally_[HABUFFER_DUPLICATE];
        continue;
      }
      const std::uint32_t start = r == lane.previous ? lane.twin_start : lane.next_start;
      lane.previous = r;
      lane.p = lane.pixel;
      lane.a = start;
      lane.iter = start - 1;  // the skipped probes count, so the iteration limit reads the same
      lane.own = true;
      if (start <= max_age_) lane.r = k_.ha_with_age(r, start);
      if (aim(lane)) return true;
    }
    return false;
  }

  // Ends the call with a failure, or points the lane at its next probe
  // (prefetched); true while the call goes on.
  bool aim(Lane& lane) {
    std::uint32_t failed = HABUFFER_PENDING;
    if (lane.a > max_age_)
      failed = HABUFFER_FAILED_AGE;
    else if (lane.iter >= iter_limit_)
      failed = HABUFFER_FAILED_ITER;
    if (failed != HABUFFER_PENDING) {
      // The record itself failed: it lost at every age before a, so will the next.
      if (lane.own) lane.next_start = lane.twin_start = lane.a;
      lane.previous_failed = true;
      ++tally_[failed];
      return false;
    }
    lane.slot = k_.ha_slot(k_.ha_probe(lane.p, lane.a));
    if constexpr (Prefetch) __builtin_prefetch(k_.slots() + lane.slot, 1);
    return true;
  }

  // The pixel's record was written (stored, placed by eviction, or met its
  // twin) at the lane's age: a smaller record starts one age further, a twin there.
  static void written(Lane& lane) {
    if (!lane.own) return;
    lane.own = false;
    lane.next_start = lane.a + 1;
    lane.twin_start = lane.a;
  }

  // One probe; true when the call has ended (its outcome tallied).
  bool step(Lane& lane) {
    const Word seen = k_.ha_load_slot(lane.slot);
    if (seen < lane.r) {
      const Word old = k_.ha_atomic_max_slot(lane.slot, lane.r);
      if (old < lane.r) return placed(lane, old);
      if (old == lane.r) return duplicate(lane);
    } else if (seen == lane.r) {
      // The shared step would take the atomic here and find r itself.
      return duplicate(lane);
    }
    ++lane.iter;  // lost to a larger record: the next age
    return advance(lane);
  }

  bool duplicate(Lane& lane) {
    ++lane.iter;
    written(lane);
    lane.previous_failed = false;
    ++tally_[HABUFFER_DUPLICATE];
    return true;
  }

  // r took the slot from `old` (0: an empty slot).
  bool placed(Lane& lane, Word old) {
    ++lane.iter;
    k_.ha_atomic_max_age(k_.ha_cell(lane.p), lane.a);
    written(lane);
    if (old == Word(0)) {
      lane.previous_failed = false;
      ++tally_[HABUFFER_STORED];
      return true;
    }
    // Carry the evicted record on from its own age; its pixel follows from it.
    const glm::uvec2 h = k_.ha_probe(lane.p, lane.a);
    lane.a = k_.ha_age(old);
    lane.p = k_.ha_owner(h, lane.a);
    lane.r = old;
    return advance(lane);
  }

  // The carried record moves to its next age.
  bool advance(Lane& lane) {
    ++lane.a;
    if (lane.a <= max_age_) lane.r = k_.ha_with_age(lane.r, lane.a);
    if (aim(lane)) return false;
    return true;
  }

  Kernel& k_;
  std::uint64_t* tally_;
  std::uint32_t max_age_, iter_limit_;
  std::array<Lane, Lanes> lanes_{};
};

}  // namespace habuffer::detail
