#include "habuffer/techniques/linked_lists/linked_lists.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/techniques/linked_lists/detail/lists_kernel.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer {
LinkedLists::LinkedLists(const TechniqueConfig& config)
    : config_(validated_as(config, lists_flavour(config.technique))),
      params_(kernel_uniforms(config_)),
      heads_(config_.buffer.screen.area(), 0),
      entries_(config_.pool_capacity),
      next_(config_.pool_capacity, 0),
      saturation_(config_.buffer.saturation ? config_.buffer.screen.area() : 0, 0) {}

namespace {

// One thread's fragments set aside at a pool with no block left (node_blocks.h),
// on a cache line of its own.
struct alignas(64) SetAside {
  std::vector<std::size_t> fragments;  // indices into the batch
};

// The most fragments a thread sets aside when the pool has no block left
// (node_blocks.h): on one thread none, as no other block can hold a node;
// for lists, where every fragment takes a node, what the other threads'
// blocks can hold at most; sorted lists set aside every one, since a
// set-aside fragment may turn out a duplicate and take none.
std::size_t set_aside_limit(std::uint32_t threads, bool sorted) {
  if (threads == 1) return 0;
  return sorted ? SIZE_MAX : std::size_t{threads - 1} * NodePool::kBlock;
}

// The ranges of `ranges` cut into single nodes.
std::vector<NodeRange> one_by_one(std::span<const NodeRange> ranges) {
  std::vector<NodeRange> nodes;
  for (const NodeRange& r : ranges)
    for (std::uint32_t n = r.begin; n < r.end; ++n) nodes.push_back({n, n + 1});
  return nodes;
}

// `ranges` sorted, neighbouring ones joined, empty ones dropped.
std::vector<NodeRange> coalesced(std::vector<NodeRange> ranges) {
  std::erase_if(ranges, [](const NodeRange& r) { return r.empty(); });
  std::sort(ranges.begin(), ranges.end(), [](const NodeRange& a, const NodeRange& b) { return a.begin < b.begin; });
  std::vector<NodeRange> joined;
  for (const NodeRange& r : ranges) {
    if (!joined.empty() && joined.back().end == r.begin) joined.back().end = r.end;
    else joined.push_back(r);
  }
  return joined;
}

// What placing the set-aside fragments gave.
struct Placed {
  Counters counters;
  std::uint64_t merged = 0;  // what on_stored returned
};

// The set-aside fragments through insert(kernel, fragment) with the nodes
// of `left` (what the threads' blocks left), which keeps those still unused:
// only now, with every other node linked, is a fragment dropped. Threads
// that own their rows each place their own set-aside fragments (their own
// pixels), taking the left nodes one at a time, so that no thread holds a
// node another needs and sorted lists walk again in parallel; after slices
// of the stream, one thread places them all. on_stored(kernel, fragment)
// follows each fragment stored and returns the entries it merged.
template <class Insert, class OnStored>
Placed place_set_aside(const KernelUniforms& params, const ListsBuffers& b, std::span<const Fragment> fragments,
                       std::span<const SetAside> aside, bool owned_rows, std::vector<NodeRange>& left,
                       Insert insert, OnStored on_stored) {
  if (std::all_of(aside.begin(), aside.end(), [](const SetAside& a) { return a.fragments.empty(); })) return {};
  const auto threads = static_cast<std::uint32_t>(owned_rows ? aside.size() : 1);
  const std::vector<NodeRange> nodes = owned_rows ? one_by_one(left) : left;
  std::uint32_t no_fresh = params.ll_pool_capacity;
  NodePool rest(&no_fresh, params.ll_pool_capacity, nodes);
  std::vector<detail::SliceCounters> parts(threads);
  std::vector<detail::PartCount> merged(threads);
  std::vector<NodeRange> blocks(threads);
  run_with_threads(threads, [&] {
    fork_join(threads, [&](std::uint32_t t) {
      ListsKernel<false> k(params, b);
      k.use_nodes(rest);
      std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
      for (std::size_t a = owned_rows ? t : 0; a < (owned_rows ? t + 1 : aside.size()); ++a)
        for (const std::size_t i : aside[a].fragments) {
          const std::uint32_t outcome = insert(k, fragments[i]);
          if (outcome == HABUFFER_STORED) {
            k.ll_commit_node();
            merged[t].n += on_stored(k, fragments[i]);
          }
          ++tally[outcome];
        }
      parts[t].c.add_tally(tally);
      blocks[t] = k.unused_nodes();
    });
  });
  left = coalesced(rest.unused(blocks));
  Placed placed;
  for (std::uint32_t t = 0; t < threads; ++t) {
    placed.counters += parts[t].c;
    placed.merged += merged[t].n;
  }
  return placed;
}

// Asks the cache for the line at `p`: a hint, nothing waits for it.
void prefetch(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

// The lists of the rows `rows` visits (rows(f) calls f(y) for each) sorted
// over buffers `b`, identical entries merged; returns how many were merged.
// The sort waits on loads of nodes that lie anywhere in the pool, and most
// lists are short: so the first node of the list a few pixels ahead is
// fetched while this one is sorted (5 % on hairball). Its own kernel for
// all the rows, and everything inlined (flatten): with a kernel the
// compiler cannot keep in registers, the sort ran 10-15 % slower.
template <class Rows>
[[gnu::flatten]] std::uint64_t sort_rows(const KernelUniforms& params, ListsBuffers b, Rows rows) {
  constexpr std::uint32_t kAhead = 8;
  ListsKernel<false> k(params, b);
  const std::uint32_t width = params.habuffer_screen_size.x;
  std::uint64_t merged = 0;
  rows([&](std::uint32_t y) {
    const std::uint32_t* heads = b.heads + std::size_t{y} * width;
    for (std::uint32_t x = 0; x < width; ++x) {
      if (x + kAhead < width && heads[x + kAhead] != 0) {
        prefetch(b.entries + heads[x + kAhead] - 1);
        prefetch(b.next + heads[x + kAhead] - 1);
      }
      merged += k.ll_sort_pixel(glm::uvec2(x, y));
    }
  });
  return merged;
}

}  // namespace

template <class Insert>
Counters LinkedLists::gather(std::span<const Fragment> fragments, const detail::InsertPlan& plan, Insert insert) {
  const bool sort_after = !sorted_on_insert();
  // A thread that owns its rows sorts them as soon as it has linked its
  // fragments: no other thread links into them.
  const bool sort_own_rows = sort_after && plan.owned_rows;
  const ListsBuffers lists = buffers();
  NodePool pool(&counter_, static_cast<std::uint32_t>(capacity()), spare_);
  std::vector<NodeRange> blocks(plan.threads);  // each thread's last block, what it left of it
  std::vector<SetAside> aside(plan.threads);
  const std::size_t aside_limit = set_aside_limit(plan.threads, sorted_on_insert());
  std::vector<detail::SliceCounters> parts(plan.threads);
  std::vector<detail::PartCount> merged(plan.threads + 1);  // the last: pixels sorted after the threads
  const auto make = [&](auto concurrent) { return ListsKernel<decltype(concurrent)::value>(params_, lists); };
  const auto insert_mine = [&](auto& k, std::span<const Fragment> mine, std::uint32_t t, auto owns) {
    k.use_nodes(pool);
    // A local tally: counters in memory could alias the buffers and force a store per fragment.
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    for (const Fragment& f : mine) {
      if (!owns(f)) continue;
      const std::uint32_t outcome = insert(k, f);
      if (outcome == HABUFFER_DROPPED_POOL && aside[t].fragments.size() < aside_limit) {
        aside[t].fragments.push_back(static_cast<std::size_t>(&f - fragments.data()));
        continue;
      }
      if (outcome == HABUFFER_STORED) k.ll_commit_node();
      ++tally[outcome];
    }
    parts[t].c.add_tally(tally);
    blocks[t] = k.unused_nodes();
    if (sort_own_rows)
      merged[t].n = sort_rows(params_, lists, [&](auto row) { owns.rows(screen(), row); });
  };
  detail::for_insert_threads(fragments, screen(), plan, make, insert_mine);
  Counters c;
  for (const auto& part : parts) c += part.c;
  std::vector<NodeRange> left = pool.unused(blocks);
  const Placed late = place_set_aside(params_, lists, fragments, aside, plan.owned_rows, left, insert,
                                      [&](ListsKernel<false>& k, const Fragment& f) -> std::uint64_t {
                                        // Its pixel's list was sorted already: sort it again.
                                        return sort_own_rows ? k.ll_sort_pixel(glm::uvec2(f.x, f.y)) : 0;
                                      });
  c += late.counters;
  merged.back().n = late.merged;
  spare_ = std::move(left);
  return_to_counter(spare_, &counter_);
  requested_ += c.stored() + c.dropped_pool;  // every node asked for, duplicates included
  if (sort_after && !sort_own_rows)
    detail::for_row_bands(screen(), plan.threads, [&](std::uint32_t part, std::uint32_t y0, std::uint32_t y1) {
      merged[part].n = sort_rows(params_, lists, [&](auto row) {
        for (std::uint32_t y = y0; y < y1; ++y) row(y);
      });
    });
  for (const auto& m : merged) c.merge_duplicates(m.n);
  return c;
}

Counters LinkedLists::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  const detail::InsertPlan plan = detail::insert_plan(
      options, technique(), detail::insert_work(technique(), fragments.size(), !sorted_on_insert(), screen()));
  detail::check_on_screen(fragments, screen(), plan.threads);
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  if (requested_ + fragments.size() > UINT32_MAX)
    throw std::invalid_argument("linked lists count nodes in 32 bits: " + std::to_string(requested_ + fragments.size()) +
                                " fragments since the last clear are too many");
  if (sorted_on_insert())
    return gather(fragments, plan, [](auto& k, const Fragment& f) {
      return k.sl_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
    });
  // New nodes are prepended; gather sorts every pixel's list.
  return gather(fragments, plan, [](auto& k, const Fragment& f) {
    return k.ll_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
  });
}

ListsBuffers LinkedLists::buffers() const {
  // The kernel's read-only uses (length, composite) never write through these.
  auto* self = const_cast<LinkedLists*>(this);
  return {self->heads_.data(), self->entries_.data(), self->next_.data(), self->saturation_.data()};
}

std::uint64_t LinkedLists::clear() {
  const auto alone = gate_.alone();
  const std::uint64_t held = count_stored();
  empty();
  return held;
}

void LinkedLists::reset() {
  const auto alone = gate_.alone();
  empty();
}

void LinkedLists::empty() {
  std::fill(heads_.begin(), heads_.end(), 0u);
  std::fill(saturation_.begin(), saturation_.end(), 0u);
  counter_ = 0;
  spare_.clear();
  requested_ = 0;
}

std::uint64_t LinkedLists::count_stored() const {
  ListsKernel<false> k(params_, buffers());
  std::uint64_t n = 0;
  for (std::uint32_t head : heads_) n += k.ll_length(head);
  return n;
}

std::uint32_t LinkedLists::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  return read_linked_list(heads_, entries_, next_, x + std::size_t{y} * screen().x, out);
}

std::uint32_t read_linked_list(const std::vector<std::uint32_t>& heads, const std::vector<glm::uvec2>& entries,
                               const std::vector<std::uint32_t>& next, std::size_t pixel, std::vector<ListEntry>& out) {
  out.clear();
  std::uint32_t reads = 1;
  for (std::uint32_t l = heads[pixel]; l != 0; l = next[l - 1]) {
    out.push_back({0, entries[l - 1].x, entries[l - 1].y});
    reads += 2;
  }
  return reads;
}

std::vector<glm::vec4> LinkedLists::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  return detail::composite_image(
      screen(), backgrounds, threads, [&] { return ListsKernel<false>(params_, buffers()); },
      [](auto& k, glm::uvec2 p, glm::vec3 background) { return k.ll_composite(p, background); });
}

std::uint64_t LinkedLists::memory_bytes() const {
  return heads_.size() * 4 + entries_.size() * sizeof(glm::uvec2) + next_.size() * 4 + saturation_.size() * 4 +
         sizeof counter_;
}

void LinkedLists::import_state(std::span<const std::uint32_t> heads, std::span<const glm::uvec2> entries,
                               std::span<const std::uint32_t> next, std::uint64_t requested) {
  const auto alone = gate_.alone();
  if (heads.size() != heads_.size() || entries.size() != entries_.size() || next.size() != next_.size())
    throw std::invalid_argument("imported lists have " + std::to_string(heads.size()) + " heads and " +
                                std::to_string(entries.size()) + " nodes, the buffer " + std::to_string(heads_.size()) +
                                " and " + std::to_string(entries_.size()));
  const auto bad_link = [&](std::uint32_t l) { return l > entries_.size(); };
  if (std::any_of(heads.begin(), heads.end(), bad_link) || std::any_of(next.begin(), next.end(), bad_link))
    throw std::invalid_argument("imported lists link beyond the pool of " + std::to_string(entries_.size()) + " nodes");
  // Each node on at most one list, once (a cycle would never end a walk),
  // every list sorted with valid entries.
  const RecordLayout layout = config_.buffer.record_layout();
  ListsKernel<false> order(params_, buffers());  // the lists' entry order (ha_entries.glsl)
  const auto before = [&](glm::uvec2 a, glm::uvec2 b) { return order.ha_entry_before(a, b); };
  std::vector<bool> reached(entries.size(), false);
  std::vector<glm::uvec2> list;
  for (std::size_t p = 0; p < heads.size(); ++p) {
    list.clear();
    for (std::uint32_t l = heads[p]; l != 0; l = next[l - 1]) {
      if (reached[l - 1])
        throw std::invalid_argument("imported lists reach node " + std::to_string(l) + " twice (again from pixel (" +
                                    std::to_string(p % screen().x) + "," + std::to_string(p / screen().x) + "))");
      reached[l - 1] = true;
      list.push_back(entries[l - 1]);
    }
    detail::check_imported_list(list, layout, p, screen(), "imported lists", before);
  }
  std::copy(heads.begin(), heads.end(), heads_.begin());
  std::copy(entries.begin(), entries.end(), entries_.begin());
  std::copy(next.begin(), next.end(), next_.begin());
  requested_ = requested;
  // The GPU's counter ran past the capacity by the nodes it could not give.
  counter_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(requested, entries_.size()));
  spare_.clear();
}

}  // namespace habuffer
