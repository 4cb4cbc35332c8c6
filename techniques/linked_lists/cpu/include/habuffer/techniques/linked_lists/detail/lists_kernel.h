/// @file
/// Per-pixel linked lists on the CPU, sorted after the gather or kept sorted
/// while inserting: the shared GLSL of techniques/linked_lists/cpu/include/habuffer/techniques/linked_lists/lists.glsl and
/// sorted_lists.glsl compiled as member functions, over the buffers a
/// shader would get.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/node_blocks.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The buffers a kernel works on (what a shader gets bound).
struct ListsBuffers {
  std::uint32_t* heads;    ///< one link per pixel
  glm::uvec2* entries;     ///< (code, data) per node
  std::uint32_t* next;     ///< one link per node
  std::uint32_t* saturation;  ///< sorted lists with saturation: a code per pixel (else unused)
};

/// Concurrent: head pointers and (sorted lists) links are updated atomically
/// (several inserters at once; blocks of nodes are reserved atomically
/// always, node_blocks.h); the sort and compositing need no atomics (one
/// pixel per thread).
template <bool Concurrent>
class ListsKernel : public KernelUniforms {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The private array ha_entries.glsl sorts a pixel's entries in (glsl_env.h).
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  /// The word ha_record.glsl packs records in: 64 bits.
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;  ///< bits of ha_word

  /// The buffers the kernel works on.
  using Buffers = ListsBuffers;

  /// Reads the record layout, the screen, the pool and the sorted lists' options
  /// from `uniforms` (technique_params.h); works on the caller's buffers `b`, which it does not own.
  ListsKernel(const KernelUniforms& uniforms, const Buffers& b)
      : KernelUniforms(uniforms), b_(b) {}


  /// Inserts take nodes from blocks of `pool` (node_blocks.h).
  void use_nodes(NodePool& pool) { pool_ = &pool; }
  /// The node this kernel's next insertion may link (its block's first,
  /// reserving a block when the last is used up), or the capacity when the
  /// pool has no node left. It stays the next one until the host commits it
  /// (ll_commit_node, when an insertion returned HABUFFER_STORED), so an
  /// insertion that links nothing takes nothing; the host counts the nodes
  /// asked for from the outcomes (stored and dropped_pool).
  uint ll_allocate_node() {
    if (block_.empty()) block_ = pool_->take();
    return block_.empty() ? ll_pool_capacity : block_.begin;
  }
  /// The node ll_allocate_node gave was linked: the next insertion takes the next one.
  void ll_commit_node() { ++block_.begin; }
  /// The nodes of this kernel's block not handed out yet.
  [[nodiscard]] NodeRange unused_nodes() const { return block_; }
  /// Replaces the pixel's head by `link`; returns the old head (atomic when Concurrent).
  uint ll_exchange_head(uint pixel, uint link) {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(b_.heads[pixel]).exchange(link, std::memory_order_relaxed);
    const uint old = b_.heads[pixel];
    b_.heads[pixel] = link;
    return old;
  }
  /// The pixel's head link (0: empty list).
  uint ll_load_head(uint pixel) const { return b_.heads[pixel]; }
  /// Sets the pixel's head link.
  void ll_store_head(uint pixel, uint link) { b_.heads[pixel] = link; }
  /// The (code, data) entry of node index `node` (link - 1).
  uvec2 ll_load_entry(uint node) const { return b_.entries[node]; }
  /// Writes the entry of node index `node`.
  void ll_store_entry(uint node, uvec2 e) { b_.entries[node] = e; }
  /// The link of node index `node` (0: end of list).
  uint ll_load_next(uint node) const { return b_.next[node]; }
  /// Sets the link of node index `node`.
  void ll_store_next(uint node, uint link) { b_.next[node] = link; }

  /// Sorted lists: the link a walk reads (the head for where == 0) and the swap that links a node.
  uint& sl_link(uint pixel, uint where) const { return where == 0 ? b_.heads[pixel] : b_.next[where - 1]; }
  /// The link at `where` (see sl_link): an acquire read when Concurrent.
  uint sl_load_link(uint pixel, uint where) const {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(sl_link(pixel, where)).load(std::memory_order_acquire);
    return sl_link(pixel, where);
  }
  /// Compare-and-swap of the link at `where` from `expected` to `link`
  /// (acquire-release when Concurrent); returns the link it found.
  uint sl_swap_link(uint pixel, uint where, uint expected, uint link) {
    if constexpr (Concurrent) {
      std::atomic_ref<std::uint32_t>(sl_link(pixel, where))
          .compare_exchange_strong(expected, link, std::memory_order_acq_rel, std::memory_order_acquire);
      return expected;
    } else {
      const uint found = sl_link(pixel, where);
      if (found == expected) sl_link(pixel, where) = link;
      return found;
    }
  }
  /// The pixel's saturation code (saturation on only).
  uint ha_load_saturation(uint pixel) const { return ha_fetch<Concurrent>(b_.saturation[pixel]); }
  /// Raises the pixel's saturation code to at least `code` (atomic max).
  void ha_max_saturation(uint pixel, uint code) { ha_fetch_max<Concurrent>(b_.saturation[pixel], code); }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_entries.glsl"
#include "habuffer/techniques/linked_lists/lists.glsl"
#include "habuffer/shared/ha_saturation.glsl"
#include "habuffer/techniques/linked_lists/sorted_lists.glsl"

 private:
  Buffers b_;
  NodePool* pool_ = nullptr;  ///< where blocks come from (use_nodes)
  NodeRange block_;           ///< the nodes of the current block not handed out yet
};

}  // namespace habuffer
