#include "habuffer/techniques/paged_lists/paged_lists.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer {

PagedLists::PagedLists(const TechniqueConfig& config)
    : config_(validated_as(config, Technique::PagedLists)),
      params_(kernel_uniforms(config_)),
      heads_(config_.buffer.screen.area(), 0),
      entries_(config_.pool_capacity),
      next_(config_.pool_capacity, 0) {}

PagedListsBuffers PagedLists::buffers() const {
  // The kernel's read-only uses (length, composite) never write through these.
  auto* self = const_cast<PagedLists*>(this);
  return {self->heads_.data(), self->entries_.data(), self->next_.data(), &self->counter_, &self->wasted_};
}

Counters PagedLists::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  detail::InsertPlan plan = detail::insert_plan(
      options, Technique::PagedLists, detail::insert_work(Technique::PagedLists, fragments.size(), true, screen()));
  detail::check_on_screen(fragments, screen(), plan.threads);
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  // Each fragment adds at most one page to the counter.
  if (std::uint64_t{counter_} + std::uint64_t{fragments.size()} * kPagedListsPageNodes > UINT32_MAX)
    throw std::invalid_argument("paged lists count nodes in 32 bits: " + std::to_string(fragments.size()) +
                                " fragments in pages of " + std::to_string(kPagedListsPageNodes) + " after " +
                                std::to_string(counter_) + " nodes asked for since the last clear are too many");
  // Threads racing for the pool's last pages would make which fragments drop
  // depend on timing. A pool with a page left per fragment cannot run short
  // (each fragment opens at most one page), so threads give one thread's
  // lists and counters; a pool that might run short inserts on one thread.
  const std::uint64_t room = params_.ll_pool_capacity - std::min<std::uint64_t>(counter_, params_.ll_pool_capacity);
  if (plan.threads > 1 && room < std::uint64_t{fragments.size()} * kPagedListsPageNodes) {
    InsertOptions one = options;
    one.threads = 1;
    plan = detail::insert_plan(one, Technique::PagedLists,
                               detail::insert_work(Technique::PagedLists, fragments.size(), true, screen()));
  }
  const PagedListsBuffers b = buffers();
  const auto make = [&](auto concurrent) { return PagedListsKernel<decltype(concurrent)::value>(params_, b); };
  const auto make_sorter = [&] { return PagedListsKernel<false>(params_, b); };
  return detail::insert_then_sort(
      fragments, screen(), plan, make, make_sorter,
      [](auto& k, const Fragment& f) { return k.pl_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba); },
      [](auto& k, glm::uvec2 p) { return k.pl_sort_pixel(p); });
}

std::uint64_t PagedLists::clear() {
  const auto alone = gate_.alone();
  const std::uint64_t held = count_stored();
  empty();
  return held;
}

void PagedLists::reset() {
  const auto alone = gate_.alone();
  empty();
}

void PagedLists::empty() {
  std::fill(heads_.begin(), heads_.end(), 0u);
  counter_ = 0;
  wasted_ = 0;
}

std::uint64_t PagedLists::count_stored() const {
  PagedListsKernel<false> k(params_, buffers());
  std::uint64_t n = 0;
  for (std::uint32_t head : heads_) n += k.ll_length(head);
  return n;
}

std::uint32_t PagedLists::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  return read_linked_list(heads_, entries_, next_, x + std::size_t{y} * screen().x, out);
}

std::vector<glm::vec4> PagedLists::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  return detail::composite_image(
      screen(), backgrounds, threads, [&] { return PagedListsKernel<false>(params_, buffers()); },
      [](auto& k, glm::uvec2 p, glm::vec3 background) { return k.ll_composite(p, background); });
}

std::uint64_t PagedLists::memory_bytes() const {
  return heads_.size() * 4 + entries_.size() * sizeof(glm::uvec2) + next_.size() * 4 + sizeof counter_ + sizeof wasted_;
}

void PagedLists::import_state(std::span<const std::uint32_t> heads, std::span<const glm::uvec2> entries,
                              std::span<const std::uint32_t> next, std::uint64_t requested) {
  const auto alone = gate_.alone();
  if (heads.size() != heads_.size() || entries.size() != entries_.size() || next.size() != next_.size())
    throw std::invalid_argument("imported paged lists have " + std::to_string(heads.size()) + " heads and " +
                                std::to_string(entries.size()) + " nodes, the buffer " + std::to_string(heads_.size()) +
                                " and " + std::to_string(entries_.size()));
  if (requested > UINT32_MAX)
    throw std::invalid_argument("imported paged lists asked for " + std::to_string(requested) +
                                " nodes: beyond the 32-bit node counter");
  const auto bad_link = [&](std::uint32_t l) { return l > entries_.size(); };
  if (std::any_of(heads.begin(), heads.end(), bad_link) || std::any_of(next.begin(), next.end(), bad_link))
    throw std::invalid_argument("imported paged lists link beyond the pool of " + std::to_string(entries_.size()) +
                                " nodes");
  // Each node on at most one list, once (a cycle would never end a walk),
  // each page's nodes on one pixel's list, every list sorted with valid entries.
  const RecordLayout layout = config_.buffer.record_layout();
  PagedListsKernel<false> order(params_, buffers());  // the lists' entry order (ha_entries.glsl)
  const auto before = [&](glm::uvec2 a, glm::uvec2 b) { return order.ha_entry_before(a, b); };
  constexpr std::uint64_t kNoPixel = std::numeric_limits<std::uint64_t>::max();
  std::vector<bool> reached(entries.size(), false);
  std::vector<std::uint64_t> page_owner(entries.size() / kPagedListsPageNodes + 1, kNoPixel);
  std::vector<glm::uvec2> list;
  std::uint64_t pages_used = 0;  // past the highest page any list reaches
  for (std::size_t p = 0; p < heads.size(); ++p) {
    list.clear();
    for (std::uint32_t l = heads[p]; l != 0; l = next[l - 1]) {
      const std::string where = " (from pixel (" + std::to_string(p % screen().x) + "," +
                                std::to_string(p / screen().x) + "))";
      if (reached[l - 1]) throw std::invalid_argument("imported paged lists reach node " + std::to_string(l) + " twice" + where);
      reached[l - 1] = true;
      std::uint64_t& owner = page_owner[(l - 1) / kPagedListsPageNodes];
      if (owner != kNoPixel && owner != p)
        throw std::invalid_argument("imported paged lists share the page of node " + std::to_string(l) +
                                    " between two pixels" + where);
      owner = p;
      pages_used = std::max<std::uint64_t>(pages_used, (l - 1) / kPagedListsPageNodes + 1);
      list.push_back(entries[l - 1]);
    }
    detail::check_imported_list(list, layout, p, screen(), "imported paged lists", before);
  }
  std::copy(heads.begin(), heads.end(), heads_.begin());
  std::copy(entries.begin(), entries.end(), entries_.begin());
  std::copy(next.begin(), next.end(), next_.begin());
  // The GPU's counter ran past the capacity by the nodes it could not give.
  // (at least past every page a list holds, so no later page is one of them).
  counter_ = static_cast<std::uint32_t>(std::max<std::uint64_t>(requested, pages_used * kPagedListsPageNodes));
  wasted_ = 0;  // the GPU's count is not read back
  PagedListsKernel<false> k(params_, buffers());
  for (std::uint32_t p = 0; p < heads_.size(); ++p) k.pl_head_to_top(p);
}

}  // namespace habuffer
