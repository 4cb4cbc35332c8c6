// The parallel shapes the sorted techniques share on the CPU: a stream split
// into contiguous slices, one per thread, all inserting into the same
// buffers with atomics (the GPU's model); and a screen split into bands of
// rows, one per thread, for the per-pixel sort and compositing.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

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

// The threads and whether they share the buffers through atomics; throws for
// a mode the sorted techniques do not have.
inline std::uint32_t insert_threads(const InsertOptions& options, Technique technique) {
  const std::uint32_t threads = resolve_threads(options.threads);
  if (options.mode == InsertMode::OwnerComputes)
    throw std::invalid_argument("owner-computes insertion is the HA-buffer's, not " + to_string(technique) + "'s");
  if (options.mode == InsertMode::Serial && threads != 1)
    throw std::invalid_argument("serial insertion runs on one thread, not " + std::to_string(threads));
  return threads;
}

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

// Every pixel's list sorted by `make_kernel()`'s sort(kernel, pixel), which
// returns the entries it merged; returns them all.
template <class MakeKernel, class Sort>
std::uint64_t sort_every_pixel(Extent screen, std::uint32_t threads, MakeKernel make_kernel, Sort sort) {
  std::vector<PartCount> merged(threads);
  for_every_pixel(screen, threads, make_kernel,
                  [&](auto& k, glm::uvec2 p, std::uint32_t part) { merged[part].n += sort(k, p); });
  std::uint64_t total = 0;
  for (const PartCount& m : merged) total += m.n;
  return total;
}

// Each pixel p composited over background(p) (row-major index) by
// `make_kernel()`'s composite(kernel, pixel, background), bands of rows in parallel.
template <class MakeKernel, class Composite, class Background>
std::vector<glm::vec4> composite_pixels(Extent screen, std::uint32_t threads, MakeKernel make_kernel,
                                        Composite composite, Background background) {
  std::vector<glm::vec4> image(screen.area());
  for_every_pixel(screen, resolve_threads(threads), make_kernel, [&](auto& k, glm::uvec2 p, std::uint32_t) {
    const std::size_t i = p.x + std::size_t{p.y} * screen.x;
    image[i] = composite(k, p, background(i));
  });
  return image;
}

// The same over one background per pixel (throws for a wrong count).
template <class MakeKernel, class Composite>
std::vector<glm::vec4> composite_image(Extent screen, std::span<const glm::vec3> backgrounds, std::uint32_t threads,
                                       MakeKernel make_kernel, Composite composite) {
  if (backgrounds.size() != screen.area())
    throw std::invalid_argument("composite_image: " + std::to_string(backgrounds.size()) + " backgrounds for screen " +
                                screen.str());
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
