// Per-pixel linked lists on the CPU: the shared GLSL of core/shared/ha_lists.glsl
// compiled as member functions, over the buffers a shader would get.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

// The buffers a kernel works on (what a shader gets bound).
struct ListsBuffers {
  std::uint32_t* heads;    // one link per pixel
  glm::uvec2* entries;     // (code, data) per node
  std::uint32_t* next;     // one link per node
  std::uint32_t* counter;  // nodes asked for
};

// Concurrent: the node counter and head pointers are updated atomically
// (several inserters at once); the sort and compositing need no atomics
// (one pixel per thread).
template <bool Concurrent>
class ListsKernel {
 public:
  HA_GLSL_CLASS_PRELUDE
  HA_GLSL_CLASS_LOCAL_ARRAY
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;

  using Buffers = ListsBuffers;

  ListsKernel(const TechniqueParams& params, const Buffers& b)
      : ha_age_bits(params.age_bits),
        ha_payload_bits(params.payload_bits),
        ha_screen_size(params.screen.x, params.screen.y),
        ha_pool_capacity(params.pool_capacity),
        b_(b) {}

  uint ha_age_bits;
  uint ha_payload_bits;
  uvec2 ha_screen_size;
  uint ha_pool_capacity;

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

#include "../../shared/ha_record.glsl"
#include "../../shared/ha_blend.glsl"
#include "../../shared/ha_entries.glsl"
#include "../../shared/ha_lists.glsl"

 private:
  Buffers b_;
};

}  // namespace habuffer
