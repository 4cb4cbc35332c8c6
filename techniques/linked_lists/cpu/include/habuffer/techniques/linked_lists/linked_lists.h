/// @file
/// Per-pixel linked lists on the CPU: head pointers, a node pool of fixed
/// capacity handed to threads in blocks (node_blocks.h); either sorted after each insert batch
/// (technique lists, seed 002) or kept sorted by a lock-free insertion with
/// optional early termination and saturation depth (technique sorted-lists,
/// seed 001's PreSortLF and PreSortLF*).
/// A fragment is dropped and counted (dropped_pool) only when every node of
/// the pool holds a record, at any thread count (node_blocks.h);
/// requested() tells how many nodes the gathers since the last clear wanted
/// (stored + dropped_pool, before merging duplicates), so a caller can size
/// the next pool (adaptive sizing, lossless regathering).
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/techniques/linked_lists/detail/lists_kernel.h"
#include "habuffer/technique_params.h"

namespace habuffer {
namespace detail {
struct InsertPlan;  // how an insert call runs its threads (core/model/include/habuffer/detail/technique_parallel.h)
}  // namespace detail

/// Per-pixel linked lists, sorted after the gather or kept sorted (see above).
/// The list of the pixel at index `pixel` in node lists stored as linked
/// lists store them (a head per pixel, node + 1 or 0; entries; links, node +
/// 1 or 0), front to back into `out`; returns the words read (the head, then
/// an entry and a link per node). Paged lists store theirs the same way.
std::uint32_t read_linked_list(const std::vector<std::uint32_t>& heads, const std::vector<glm::uvec2>& entries,
                               const std::vector<std::uint32_t>& next, std::size_t pixel, std::vector<ListEntry>& out);

/// The linked-list container's technique for `t`: sorted-lists stays,
/// anything else is lists (whose container then refuses it by name).
inline Technique lists_flavour(Technique t) { return t == Technique::SortedLists ? t : Technique::Lists; }

class LinkedLists final : public FragmentBuffer {
 public:
  /// Technique sorted-lists when config.technique says so, else lists. Throws
  /// std::invalid_argument for a bad configuration (TechniqueConfig::validate).
  explicit LinkedLists(const TechniqueConfig& config);

  /// FragmentBuffer interface (see fragment_buffer.h): lists or sorted-lists.
  [[nodiscard]] Technique technique() const override { return config_.technique; }
  /// Whether fragments are linked in at their place (technique sorted-lists).
  [[nodiscard]] bool sorted_on_insert() const { return config_.technique == Technique::SortedLists; }
  /// FragmentBuffer interface: the screen, in pixels.
  [[nodiscard]] Extent screen() const override { return config_.buffer.screen; }
  /// The configuration, validated as lists or sorted-lists.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// FragmentBuffer interface: the same configuration.
  [[nodiscard]] TechniqueConfig technique_config() const override { return config_; }

  /// FragmentBuffer interface: lists sort every pixel's list after the batch;
  /// sorted-lists link each fragment in at its place. Throws std::invalid_argument
  /// for InsertMode::OwnerComputes, Serial with more than one thread, or more than
  /// 2^32 - 1 fragments since the last clear. Each call runs alone: calls
  /// overlapping on this container wait for it (insert_gate.h).
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// FragmentBuffer interface: empties every list and resets the node counter and requested().
  std::uint64_t clear() override;
  /// The same without counting the lists (a kept container's next frame).
  void reset() override;
  /// The nodes linked into the lists.
  [[nodiscard]] std::uint64_t count_stored() const override;
  /// The pool's nodes.
  [[nodiscard]] std::uint64_t capacity() const override { return params_.ll_pool_capacity; }
  /// Nodes asked for since the last clear, including those the pool could not give.
  [[nodiscard]] std::uint64_t requested() const { return requested_; }
  /// FragmentBuffer interface: the nodes asked for (requested()).
  [[nodiscard]] GrowthNeed growth_need() const override { return {requested_, 0}; }

  /// FragmentBuffer interface; returns 1 + 2 per node (the head, then each node's entry and link).
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// FragmentBuffer interface; throws std::invalid_argument unless `backgrounds`
  /// has screen area entries.
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;
  /// Head pointers, nodes (entry and link) and the counter.
  [[nodiscard]] std::uint64_t memory_bytes() const override;

  /// The GPU path's read-back: heads, node entries and links, and the nodes
  /// asked for; throws std::invalid_argument when the sizes differ from this
  /// buffer's or a link points outside the pool.
  void import_state(std::span<const std::uint32_t> heads, std::span<const glm::uvec2> entries,
                    std::span<const std::uint32_t> next, std::uint64_t requested);

 private:
  // Empties every list (the caller holds the container alone).
  void empty();
  [[nodiscard]] ListsBuffers buffers() const;
  /// Every fragment through insert(kernel, fragment), which returns the
  /// HABUFFER_* outcome, on the threads of `plan` with nodes from blocks
  /// (node_blocks.h); lists (not sorted-lists) then sorted, identical
  /// entries merged. Adds the nodes asked for to requested(); returns the
  /// tallied outcomes.
  template <class Insert>
  Counters gather(std::span<const Fragment> fragments, const detail::InsertPlan& plan, Insert insert);

  TechniqueConfig config_;
  KernelUniforms params_;
  std::vector<std::uint32_t> heads_;
  std::vector<glm::uvec2> entries_;
  std::vector<std::uint32_t> next_;
  std::vector<std::uint32_t> saturation_;  ///< sorted lists with saturation: a code per pixel
  std::uint32_t counter_ = 0;  ///< the first node never handed out since the last clear
  std::vector<NodeRange> spare_;  ///< nodes earlier calls reserved and left unused: handed out first
  std::uint64_t requested_ = 0;
};

}  // namespace habuffer
