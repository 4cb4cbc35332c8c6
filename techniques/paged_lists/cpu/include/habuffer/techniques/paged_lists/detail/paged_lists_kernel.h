/// @file
/// Paged per-pixel lists on the CPU: the shared GLSL of
/// techniques/paged_lists/cpu/include/habuffer/techniques/paged_lists/paged_lists.glsl (and the
/// linked lists' sort and compositing, lists.glsl) compiled as member
/// functions, over the buffers a shader would get.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The buffers a paged-lists kernel works on (what a shader gets bound).
struct PagedListsBuffers {
  std::uint32_t* heads;    ///< one link per pixel: its last linked node + 1
  glm::uvec2* entries;     ///< (code, data) per node
  std::uint32_t* next;     ///< one link per node
  std::uint32_t* counter;  ///< nodes handed out in pages (counts on past the capacity)
  std::uint32_t* wasted;   ///< pages allocated and never linked
};

/// Concurrent: heads are read and swapped atomically (several inserters
/// into the same pixels: slices of the stream). The page counter and the
/// wasted-page count are atomic always (threads that own their rows still
/// share the pool). The sort and compositing need no atomics (one pixel per
/// thread).
template <bool Concurrent>
class PagedListsKernel : public KernelUniforms {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The private array ha_entries.glsl sorts a pixel's entries in (glsl_env.h).
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  /// The word ha_record.glsl packs records in: 64 bits.
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;  ///< bits of ha_word

  /// The buffers the kernel works on.
  using Buffers = PagedListsBuffers;

  /// Reads the record layout, the screen, the pool and the iteration limit
  /// from `uniforms` (technique_params.h); works on the caller's buffers `b`, which it does not own.
  PagedListsKernel(const KernelUniforms& uniforms, const Buffers& b)
      : KernelUniforms(uniforms), b_(b) {}


  /// The pixel's head (a relaxed atomic read when Concurrent).
  uint pl_load_head(uint pixel) const { return ha_fetch<Concurrent>(b_.heads[pixel]); }
  /// Compare-and-swap of the pixel's head from `expected` to `link`; returns the head it found.
  uint pl_swap_head(uint pixel, uint expected, uint link) {
    if constexpr (Concurrent) {
      std::atomic_ref<std::uint32_t>(b_.heads[pixel])
          .compare_exchange_strong(expected, link, std::memory_order_relaxed, std::memory_order_relaxed);
      return expected;
    } else {
      const uint found = b_.heads[pixel];
      if (found == expected) b_.heads[pixel] = link;
      return found;
    }
  }
  /// A page's first node: the counter's old value, HABUFFER_PAGE_NODES added (atomic).
  uint pl_allocate_page() {
    return std::atomic_ref<std::uint32_t>(*b_.counter).fetch_add(kPageNodes, std::memory_order_relaxed);
  }
  /// Counts a page allocated and never linked (atomic).
  void pl_waste_page() { std::atomic_ref<std::uint32_t>(*b_.wasted).fetch_add(1, std::memory_order_relaxed); }

  /// lists.glsl's allocation, which paged lists do not call: no node.
  uint ll_allocate_node() const { return ll_pool_capacity; }
  /// lists.glsl's exchange, which paged lists do not call (plain).
  uint ll_exchange_head(uint pixel, uint link) {
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

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_entries.glsl"
#include "habuffer/techniques/linked_lists/lists.glsl"
#include "habuffer/techniques/paged_lists/paged_lists.glsl"

  /// K, the nodes of a page.
  static constexpr uint kPageNodes = HABUFFER_PAGE_NODES;

 private:
  Buffers b_;
};

/// K, the nodes of a page (paged_lists.glsl).
inline constexpr std::uint32_t kPagedListsPageNodes = PagedListsKernel<false>::kPageNodes;

}  // namespace habuffer
