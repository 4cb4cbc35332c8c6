/// @file
/// Per-pixel linked lists on the CPU, sorted after the gather or kept sorted
/// while inserting: the shared GLSL of core/include/habuffer/shared/ha_lists.glsl and
/// ha_sorted_lists.glsl compiled as member functions, over the buffers a
/// shader would get.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The buffers a kernel works on (what a shader gets bound).
struct ListsBuffers {
  std::uint32_t* heads;    ///< one link per pixel
  glm::uvec2* entries;     ///< (code, data) per node
  std::uint32_t* next;     ///< one link per node
  std::uint32_t* counter;  ///< nodes asked for
  std::uint32_t* saturation;  ///< sorted lists with saturation: a code per pixel (else unused)
};

/// Concurrent: the node counter, head pointers and (sorted lists) links are
/// updated atomically (several inserters at once); the sort and compositing
/// need no atomics (one pixel per thread).
template <bool Concurrent>
class ListsKernel {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;

  using Buffers = ListsBuffers;

  ListsKernel(const TechniqueParams& params, const Buffers& b)
      : ha_age_bits(params.age_bits),
        ha_payload_bits(params.payload_bits),
        ha_screen_size(params.screen.x, params.screen.y),
        ha_pool_capacity(params.pool_capacity),
        ha_iter_limit(params.iter_limit),
        ha_cull_tau(params.cull_tau),
        ha_saturation(params.saturation ? 1u : 0u),
        b_(b) {}

  uint ha_age_bits;
  uint ha_payload_bits;
  uvec2 ha_screen_size;
  uint ha_pool_capacity;
  uint ha_iter_limit;
  float ha_cull_tau;
  uint ha_saturation;

  uint ll_allocate_node() {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(*b_.counter).fetch_add(1, std::memory_order_relaxed);
    return (*b_.counter)++;
  }
  uint ll_exchange_head(uint pixel, uint link) {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(b_.heads[pixel]).exchange(link, std::memory_order_relaxed);
    const uint old = b_.heads[pixel];
    b_.heads[pixel] = link;
    return old;
  }
  uint ll_load_head(uint pixel) const { return b_.heads[pixel]; }
  void ll_store_head(uint pixel, uint link) { b_.heads[pixel] = link; }
  uvec2 ll_load_entry(uint node) const { return b_.entries[node]; }
  void ll_store_entry(uint node, uvec2 e) { b_.entries[node] = e; }
  uint ll_load_next(uint node) const { return b_.next[node]; }
  void ll_store_next(uint node, uint link) { b_.next[node] = link; }

  /// Sorted lists: the link a walk reads (the head for where == 0) and the swap that links a node.
  uint& sl_link(uint pixel, uint where) const { return where == 0 ? b_.heads[pixel] : b_.next[where - 1]; }
  uint sl_load_link(uint pixel, uint where) const {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(sl_link(pixel, where)).load(std::memory_order_acquire);
    return sl_link(pixel, where);
  }
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
  uint ha_load_saturation(uint pixel) const { return ha_fetch<Concurrent>(b_.saturation[pixel]); }
  void ha_max_saturation(uint pixel, uint code) { ha_fetch_max<Concurrent>(b_.saturation[pixel], code); }

#include "shared/ha_record.glsl"
#include "shared/ha_blend.glsl"
#include "shared/ha_entries.glsl"
#include "shared/ha_lists.glsl"
#include "shared/ha_saturation.glsl"
#include "shared/ha_sorted_lists.glsl"

 private:
  Buffers b_;
};

}  // namespace habuffer
