#include "habuffer/linked_lists.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/lists_kernel.h"
#include "technique_parallel.h"

namespace habuffer {
LinkedLists::LinkedLists(const TechniqueConfig& config)
    : config_(validated_as(config, lists_flavour(config.technique))),
      params_(make_technique_params(config_)),
      heads_(config_.buffer.screen.area(), 0),
      entries_(config_.pool_capacity),
      next_(config_.pool_capacity, 0),
      saturation_(config_.buffer.saturation ? config_.buffer.screen.area() : 0, 0) {}

Counters LinkedLists::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  check_on_screen(fragments, screen());
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  const std::uint32_t threads = detail::insert_threads(options, technique());
  if (requested_ + fragments.size() > UINT32_MAX)
    throw std::invalid_argument("linked lists count nodes in 32 bits: " + std::to_string(requested_ + fragments.size()) +
                                " fragments since the last clear are too many");
  const auto make = [&](auto concurrent) { return ListsKernel<decltype(concurrent)::value>(params_, buffers()); };
  if (sorted_on_insert()) {
    Counters c = detail::insert_slices(fragments, threads, make, [](auto& k, const Fragment& f) {
      return k.sl_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.rgba);
    });
    requested_ = counter_;
    return c;
  }
  Counters c = detail::insert_slices(fragments, threads, make, [](auto& k, const Fragment& f) {
    return k.ll_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.rgba);
  });
  requested_ = counter_;
  // Sort every pixel's list (new nodes were prepended), merging identical entries.
  c.merge_duplicates(detail::sort_every_pixel(
      screen(), threads, [&] { return ListsKernel<false>(params_, buffers()); },
      [](auto& k, glm::uvec2 p) { return k.ll_sort_pixel(p); }));
  return c;
}

ListsBuffers LinkedLists::buffers() const {
  // The kernel's read-only uses (length, composite) never write through these.
  auto* self = const_cast<LinkedLists*>(this);
  return {self->heads_.data(), self->entries_.data(), self->next_.data(), &self->counter_, self->saturation_.data()};
}

std::uint64_t LinkedLists::clear() {
  const auto alone = gate_.alone();
  const std::uint64_t held = count_stored();
  std::fill(heads_.begin(), heads_.end(), 0u);
  std::fill(saturation_.begin(), saturation_.end(), 0u);
  counter_ = 0;
  requested_ = 0;
  return held;
}

std::uint64_t LinkedLists::count_stored() const {
  ListsKernel<false> k(params_, buffers());
  std::uint64_t n = 0;
  for (std::uint32_t head : heads_) n += k.ll_length(head);
  return n;
}

std::uint32_t LinkedLists::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  out.clear();
  std::uint32_t reads = 1;
  for (std::uint32_t l = heads_[x + std::size_t{y} * screen().x]; l != 0; l = next_[l - 1]) {
    out.push_back({0, entries_[l - 1].x, entries_[l - 1].y});
    reads += 2;
  }
  return reads;
}

std::vector<glm::vec4> LinkedLists::composite_image(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
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
  counter_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(requested, UINT32_MAX));
}

}  // namespace habuffer
