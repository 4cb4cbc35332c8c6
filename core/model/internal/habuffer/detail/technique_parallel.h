// Internal to the project (core/model/internal: never installed). The
// parallel shapes the techniques share on the CPU: a stream split into
// contiguous slices, one per thread, all inserting into the same buffers
// with atomics (the GPU's model); the screen's rows dealt out to threads,
// each inserting its own pixels' fragments with plain stores and sorting
// its own lists (the default, insert_plan); and a screen split into bands of
// rows, one per thread, for a sort after slices and for compositing.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/fragment_buffer.h"
#include "habuffer/parallel.h"
#include "habuffer/record_layout.h"

namespace habuffer::detail {

// One cache line per thread's counters, so threads never share one.
struct alignas(64) SliceCounters {
  Counters c;
};

// A count per thread, one cache line each.
struct alignas(64) PartCount {
  std::uint64_t n = 0;
};

// How a technique's insert call runs its threads (insert_plan).
struct InsertPlan {
  std::uint32_t threads = 1;
  // Rows of pixels dealt out to the threads (true), or the stream split into
  // slices that share the buffers through atomics (false).
  bool owned_rows = false;
  std::uint32_t band_rows = 16;  // rows per band when owned_rows
};

// Work items of an insert call, for the default thread count
// (resolve_threads): one per fragment; one per pixel of a pass over every
// pixel (`pixel_pass`: the lists' and arrays' sort, the k-buffer's
// occupancy count); and for blending one per 16 fragments, since blending a
// fragment costs about what reading it costs and every thread reads the
// whole batch (two threads: 1.0x at 1 M fragments of hairball, 1.39x at 2 M).
inline std::uint64_t insert_work(Technique technique, std::uint64_t fragments, bool pixel_pass, Extent screen) {
  if (!stores_lists(technique)) return fragments / 16;
  return fragments + (pixel_pass ? screen.area() : 0);
}

// The plan for `options` over a batch of `work` items (insert_work) of `technique`;
// throws for a bad count or mode (owner-computes is the HA-buffer's). One
// thread (Serial, or a count of 1): the stream in order, plain stores.
// Atomic: contiguous slices of the stream sharing every buffer through
// atomics, the GPU's model. Auto: the screen's rows dealt out in bands of
// options.band_rows, round robin (as owner_computes.h deals the
// HA-buffer's table), and each thread inserts the fragments of its own
// pixels in stream order with plain loads and stores: no atomics, a cache
// line written by two threads only at band edges, and every pixel sees its
// fragments in the order one thread would, so the results are those of one
// thread, bit for bit, for every count. Threads 0: resolve_threads(0,
// work).
inline InsertPlan insert_plan(const InsertOptions& options, Technique technique, std::uint64_t work) {
  if (options.mode == InsertMode::OwnerComputes)
    throw std::invalid_argument("owner-computes insertion is the HA-buffer's, not " + to_string(technique) + "'s");
  InsertPlan plan;
  plan.threads = resolve_threads(options.threads, work);
  if (options.mode == InsertMode::Serial && plan.threads != 1)
    throw std::invalid_argument("serial insertion runs on one thread, not " + std::to_string(plan.threads));
  if (options.band_rows == 0) throw std::invalid_argument("band_rows must be at least 1");
  plan.owned_rows = plan.threads > 1 && options.mode != InsertMode::Atomic;
  plan.band_rows = options.band_rows;
  return plan;
}

// visit(t, fragment) for every fragment of slice t of `threads` contiguous
// slices of the stream, in parallel, each slice up to its first fragment
// off the screen; then throws as check_on_screen (fragment_buffer.h),
// naming the first fragment off the screen, if there is one.
template <class Visit>
void for_slices_on_screen(std::span<const Fragment> frags, Extent screen, std::uint32_t threads, Visit visit) {
  std::vector<PartCount> first_off(threads);
  const auto run = [&](std::uint32_t t) {
    const std::size_t begin = frags.size() * t / threads, end = frags.size() * (t + 1) / threads;
    std::size_t i = begin;
    for (; i < end && frags[i].x < screen.x && frags[i].y < screen.y; ++i) visit(t, frags[i]);
    first_off[t].n = i < end ? i : frags.size();
  };
  if (threads == 1)
    run(0);
  else
    run_with_threads(threads, [&] { fork_join(threads, run); });
  for (const PartCount& f : first_off)
    if (f.n < frags.size()) habuffer::check_on_screen(frags.first(f.n + 1), screen);  // throws, naming it
}

// check_on_screen (fragment_buffer.h) on `threads` slices in parallel:
// throws as it does, naming the first fragment off the screen. One thread
// reading the whole batch took 4-5 % of the lists' time on hairball.
inline void check_on_screen(std::span<const Fragment> frags, Extent screen, std::uint32_t threads) {
  if (threads == 1) return habuffer::check_on_screen(frags, screen);
  for_slices_on_screen(frags, screen, threads, [](std::uint32_t, const Fragment&) {});
}

// Every fragment is thread 0's (one thread, or slices of the stream).
struct AnyRow {
  bool operator()(const Fragment&) const { return true; }
  // f(y) for every row of `screen`.
  template <class F>
  void rows(Extent screen, F f) const {
    for (std::uint32_t y = 0; y < screen.y; ++y) f(y);
  }
};

// Thread `t`'s rows: bands of rows dealt out round robin (RowOwners).
struct OwnRows {
  const std::uint16_t* owner;  // per row: the thread that owns it
  std::uint16_t t;
  bool operator()(const Fragment& f) const { return owner[f.y] == t; }
  // f(y) for each of thread t's rows of `screen`.
  template <class F>
  void rows(Extent screen, F f) const {
    for (std::uint32_t y = 0; y < screen.y; ++y)
      if (owner[y] == t) f(y);
  }
};

// Which thread owns each row: bands of `band_rows` rows dealt out round
// robin to `threads` threads, so a frame whose fragments crowd part of the
// screen still gives every thread its share. A table, not a division per
// fragment.
class RowOwners {
 public:
  RowOwners(std::uint32_t rows, std::uint32_t threads, std::uint32_t band_rows) : owner_(rows) {
    static_assert(kMaxThreads <= UINT16_MAX + 1u, "a thread index fits 16 bits");
    for (std::uint32_t y = 0; y < rows; ++y) owner_[y] = static_cast<std::uint16_t>(y / band_rows % threads);
  }
  [[nodiscard]] OwnRows of(std::uint32_t t) const { return {owner_.data(), static_cast<std::uint16_t>(t)}; }

 private:
  std::vector<std::uint16_t> owner_;
};

// The stream split into contiguous slices, one per thread: each thread's
// `make_kernel(concurrent)` (a bool_constant telling whether atomics are
// needed: false for one thread, unless `shared`: other calls may insert into
// the same buffers at the same time) runs run(kernel, slice, thread).
template <class MakeKernel, class Run>
void for_slices(std::span<const Fragment> frags, std::uint32_t threads, MakeKernel make_kernel, Run run,
                bool shared = false) {
  if (threads == 1) {
    if (shared) {
      auto k = make_kernel(std::true_type{});
      run(k, frags, 0u);
    } else {
      auto k = make_kernel(std::false_type{});
      run(k, frags, 0u);
    }
    return;
  }
  run_with_threads(threads, [&] {
    fork_join(threads, [&](std::uint32_t t) {
      auto k = make_kernel(std::true_type{});
      const std::size_t begin = frags.size() * t / threads, end = frags.size() * (t + 1) / threads;
      run(k, frags.subspan(begin, end - begin), t);
    });
  });
}

// The threads of `plan` over `frags`: each runs run(kernel, fragments, t,
// mine) and inserts each f of `fragments` with mine(f) (an AnyRow or
// OwnRows, whose rows() are the pixels it alone touched), with the kernel
// make_kernel(concurrent) gives (a bool_constant telling whether atomics
// are needed: only for slices of the stream on several threads).
template <class MakeKernel, class Run>
void for_insert_threads(std::span<const Fragment> frags, Extent screen, const InsertPlan& plan, MakeKernel make_kernel,
                        Run run) {
  if (!plan.owned_rows) {
    for_slices(frags, plan.threads, make_kernel,
               [&](auto& k, std::span<const Fragment> slice, std::uint32_t t) { run(k, slice, t, AnyRow{}); });
    return;
  }
  const RowOwners owners(screen.y, plan.threads, plan.band_rows);
  run_with_threads(plan.threads, [&] {
    fork_join(plan.threads, [&](std::uint32_t t) {
      auto k = make_kernel(std::false_type{});
      run(k, frags, t, owners.of(t));
    });
  });
}

// body(part, y_begin, y_end) over `parts` bands of rows, in parallel.
template <class Body>
void for_row_bands(Extent screen, std::uint32_t parts, Body body) {
  run_with_threads(parts, [&] {
    fork_join(parts, [&](std::uint32_t part) {
      body(part, static_cast<std::uint32_t>(std::uint64_t{screen.y} * part / parts),
           static_cast<std::uint32_t>(std::uint64_t{screen.y} * (part + 1) / parts));
    });
  });
}

// sort(kernel, pixel) over the pixels of the rows `rows` visits (rows(f)
// calls f(y) for each), with one kernel make_kernel() gives; returns the sum
// of what sort returns (the entries it merged). One kernel for all the rows
// and everything inlined (flatten): a kernel the compiler cannot keep in
// registers is reloaded after every store, which made the lists' sort
// 10-15 % slower.
template <class MakeKernel, class Sort, class Rows>
[[gnu::flatten]] std::uint64_t sort_rows(Extent screen, MakeKernel make_kernel, Sort sort, Rows rows) {
  auto k = make_kernel();
  std::uint64_t merged = 0;
  rows([&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < screen.x; ++x) merged += sort(k, glm::uvec2(x, y));
  });
  return merged;
}

// The same over bands of rows, in parallel (the sort after slices of the stream).
template <class MakeKernel, class Sort>
std::uint64_t sort_row_bands(Extent screen, std::uint32_t threads, MakeKernel make_kernel, Sort sort) {
  std::vector<PartCount> merged(threads);
  for_row_bands(screen, threads, [&](std::uint32_t part, std::uint32_t y0, std::uint32_t y1) {
    merged[part].n = sort_rows(screen, make_kernel, sort, [&](auto f) {
      for (std::uint32_t y = y0; y < y1; ++y) f(y);
    });
  });
  std::uint64_t total = 0;
  for (const PartCount& m : merged) total += m.n;
  return total;
}

// The insertion of a technique that sorts after the gather: each thread
// inserts its share (insert_one(kernel, fragment) returns the HA_* outcome,
// tallied locally: counters in memory could alias the buffers and force a
// store per fragment); a thread that owns its rows sorts them at once (no
// other thread writes them), else bands of rows are sorted after the
// gather. Returns the outcomes with the entries the sort merged counted as
// duplicates.
template <class MakeKernel, class MakeSorter, class InsertOne, class Sort>
Counters insert_then_sort(std::span<const Fragment> fragments, Extent screen, const InsertPlan& plan,
                          MakeKernel make_kernel, MakeSorter make_sorter, InsertOne insert_one, Sort sort) {
  std::vector<SliceCounters> parts(plan.threads);
  std::vector<PartCount> merged(plan.threads);
  const auto insert_mine = [&](auto& k, std::span<const Fragment> mine, std::uint32_t t, auto owns) {
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    for (const Fragment& f : mine)
      if (owns(f)) ++tally[insert_one(k, f)];
    parts[t].c.add_tally(tally);
    if (plan.owned_rows)
      merged[t].n = sort_rows(screen, make_sorter, sort, [&](auto row) { owns.rows(screen, row); });
  };
  for_insert_threads(fragments, screen, plan, make_kernel, insert_mine);
  Counters c;
  for (const auto& part : parts) c += part.c;
  if (!plan.owned_rows) merged.assign(1, {sort_row_bands(screen, plan.threads, make_sorter, sort)});
  for (const auto& m : merged) c.merge_duplicates(m.n);
  return c;
}

// Every fragment through insert(kernel, fragment), which returns the HA_*
// outcome, on contiguous slices (atomics when `shared`, as for_slices);
// returns the tallied outcomes.
template <class MakeKernel, class Insert>
Counters insert_slices(std::span<const Fragment> frags, std::uint32_t threads, MakeKernel make_kernel, Insert insert,
                       bool shared = false) {
  std::vector<SliceCounters> slices(threads);
  for_slices(frags, threads, make_kernel, [&](auto& k, std::span<const Fragment> slice, std::uint32_t t) {
    // A local tally: counters in memory could alias the buffers and force a store per fragment.
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    for (const Fragment& f : slice) ++tally[insert(k, f)];
    slices[t].c.add_tally(tally);
  }, shared);
  Counters total;
  for (const auto& s : slices) total += s.c;
  return total;
}

// visit(kernel, pixel) for every pixel, bands of rows in parallel, one
// `make_kernel()` per band.
template <class MakeKernel, class Visit>
void for_every_pixel(Extent screen, std::uint32_t threads, MakeKernel make_kernel, Visit visit) {
  for_row_bands(screen, threads, [&](std::uint32_t part, std::uint32_t y0, std::uint32_t y1) {
    auto k = make_kernel();
    for (std::uint32_t y = y0; y < y1; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x) visit(k, glm::uvec2(x, y), part);
  });
}

// Each pixel p composited over background(p) (row-major index) by
// `make_kernel()`'s composite(kernel, pixel, background), bands of rows in parallel.
template <class MakeKernel, class Composite, class Background>
std::vector<glm::vec4> composite_pixels(Extent screen, std::uint32_t threads, MakeKernel make_kernel,
                                        Composite composite, Background background) {
  std::vector<glm::vec4> image(screen.area());
  for_every_pixel(screen, resolve_threads(threads, screen.area()), make_kernel, [&](auto& k, glm::uvec2 p, std::uint32_t) {
    const std::size_t i = p.x + std::size_t{p.y} * screen.x;
    image[i] = composite(k, p, background(i));
  });
  return image;
}

// Throws std::invalid_argument unless there is one background per pixel.
inline void check_backgrounds(Extent screen, std::span<const glm::vec3> backgrounds) {
  if (backgrounds.size() != screen.area())
    throw std::invalid_argument("composite_image: " + std::to_string(backgrounds.size()) + " backgrounds for screen " +
                                screen.str());
}

// The same over one background per pixel (throws for a wrong count).
template <class MakeKernel, class Composite>
std::vector<glm::vec4> composite_image(Extent screen, std::span<const glm::vec3> backgrounds, std::uint32_t threads,
                                       MakeKernel make_kernel, Composite composite) {
  check_backgrounds(screen, backgrounds);
  return composite_pixels(screen, threads, make_kernel, composite, [&](std::size_t p) { return backgrounds[p]; });
}

// Throws std::invalid_argument unless `entries`, pixel `pixel`'s imported
// list nearest first, could have been built: codes within the layout's,
// data 0 in L32, each entry strictly `before(previous, entry)` behind the
// one before it (sorted, identical entries merged; `before` is the
// technique's own order, e.g. ha_entries.glsl's ha_entry_before). `what`
// names the container.
template <class Before>
void check_imported_list(std::span<const glm::uvec2> entries, const RecordLayout& layout, std::size_t pixel,
                         Extent screen, const char* what, Before before) {
  const auto where = [&](std::size_t k) {
    return std::string(what) + ": entry " + std::to_string(k) + " of pixel (" + std::to_string(pixel % screen.x) + "," +
           std::to_string(pixel / screen.x) + ")";
  };
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const glm::uvec2 e = entries[k];
    if (e.x > layout.max_code())
      throw std::invalid_argument(where(k) + " has depth code " + std::to_string(e.x) + ", above the layout's " +
                                  std::to_string(layout.max_code()));
    if (!layout.has_data() && e.y != 0)
      throw std::invalid_argument(where(k) + " has data " + std::to_string(e.y) + " in the L32 layout (which has none)");
    if (k > 0 && !before(entries[k - 1], e))
      throw std::invalid_argument(where(k) + " is not behind the entry before it (lists are sorted, identical entries merged)");
  }
}

}  // namespace habuffer::detail
