/// @file
/// Paged per-pixel lists on the CPU (technique paged-lists, seed 000's
/// "paged lists"): linked lists whose nodes are taken in pages of
/// kPagedListsPageNodes consecutive nodes per pixel (paged_lists.glsl),
/// sorted after each insert batch as `lists` are, identical entries merged,
/// so the lists equal the HA-buffer's when nothing is dropped.
/// A fragment is dropped and counted (dropped_pool) when its pixel's page is
/// full and the pool has no page left (pages are the pool's first
/// floor(capacity / K) blocks of K nodes); requested() tells how many nodes
/// the gathers since the last clear asked for in pages (dropped ones
/// included), so a caller can size the next pool (lossless regathering).
/// With several threads the lists are those of one thread; only which
/// nodes hold them differs (and, with a pool too small, which fragments drop).
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/technique_params.h"
#include "habuffer/techniques/paged_lists/detail/paged_lists_kernel.h"

namespace habuffer {

/// Paged per-pixel lists (see above).
class PagedLists final : public FragmentBuffer {
 public:
  /// Throws std::invalid_argument for a bad configuration (TechniqueConfig::validate).
  explicit PagedLists(const TechniqueConfig& config);

  /// FragmentBuffer interface (see fragment_buffer.h): paged-lists.
  [[nodiscard]] Technique technique() const override { return Technique::PagedLists; }
  /// FragmentBuffer interface: the screen, in pixels.
  [[nodiscard]] Extent screen() const override { return config_.buffer.screen; }
  /// The configuration, validated.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// FragmentBuffer interface: the same configuration.
  [[nodiscard]] TechniqueConfig technique_config() const override { return config_; }

  /// FragmentBuffer interface: links every fragment (threads as the other
  /// containers: rows owned by threads, or slices of the stream with
  /// atomics), then sorts every pixel's list, merging identical entries.
  /// Throws std::invalid_argument for InsertMode::OwnerComputes, Serial with
  /// more than one thread, or a node counter that could pass 2^32 - 1. Each
  /// call runs alone (insert_gate.h).
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// FragmentBuffer interface: empties every list and resets the counters.
  std::uint64_t clear() override;
  /// The same without counting the lists (a kept container's next frame).
  void reset() override;
  /// The nodes linked into the lists.
  [[nodiscard]] std::uint64_t count_stored() const override;
  /// The pool's nodes.
  [[nodiscard]] std::uint64_t capacity() const override { return params_.ll_pool_capacity; }
  /// Nodes asked for in pages since the last clear, including those the pool could not give.
  [[nodiscard]] std::uint64_t requested() const { return counter_; }
  /// Pages allocated and never linked since the last clear (races between inserting threads).
  [[nodiscard]] std::uint64_t wasted_pages() const { return wasted_; }
  /// FragmentBuffer interface: the nodes asked for (requested()).
  [[nodiscard]] GrowthNeed growth_need() const override { return {requested(), 0}; }

  /// FragmentBuffer interface; returns 1 + 2 per node (the head, then each node's entry and link).
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// FragmentBuffer interface; throws std::invalid_argument unless `backgrounds`
  /// has screen area entries.
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;
  /// Head pointers, nodes (entry and link), the node counter and the wasted-page count.
  [[nodiscard]] std::uint64_t memory_bytes() const override;

  /// The GPU path's read-back: heads, node entries and links, and the nodes
  /// asked for; throws std::invalid_argument when the sizes differ from this
  /// buffer's, a link points outside the pool, a node is reached twice, a
  /// page holds nodes of two pixels or a list is not sorted. Each list is
  /// then started at its highest node (pl_head_to_top).
  void import_state(std::span<const std::uint32_t> heads, std::span<const glm::uvec2> entries,
                    std::span<const std::uint32_t> next, std::uint64_t requested);

 private:
  void empty();
  [[nodiscard]] PagedListsBuffers buffers() const;

  TechniqueConfig config_;
  KernelUniforms params_;
  std::vector<std::uint32_t> heads_;
  std::vector<glm::uvec2> entries_;
  std::vector<std::uint32_t> next_;
  std::uint32_t counter_ = 0;  ///< nodes handed out in pages since the last clear (past the capacity too)
  std::uint32_t wasted_ = 0;   ///< pages allocated and never linked since the last clear
};

}  // namespace habuffer
