/// @file
/// Fixed per-pixel arrays on the CPU: the shared GLSL of techniques/arrays/cpu/include/habuffer/techniques/arrays/arrays.glsl
/// compiled as member functions, over the buffers a shader would get.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The buffers a kernel works on (what a shader gets bound).
struct ArraysBuffers {
  std::uint32_t* counts;       ///< one per pixel
  glm::uvec2* layers;          ///< K per pixel, layer-major
  std::uint32_t* max_arrived;  ///< the largest count of a pixel that overflowed
};

/// Concurrent: the per-pixel counters are incremented atomically (several
/// inserters at once); the sort and compositing need no atomics (one pixel
/// per thread), except the note of the largest overflow.
template <bool Concurrent>
class ArraysKernel : public KernelUniforms {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The private array ha_entries.glsl sorts a pixel's entries in (glsl_env.h).
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  /// The word ha_record.glsl packs records in: 64 bits.
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;  ///< bits of ha_word

  /// The buffers the kernel works on.
  using Buffers = ArraysBuffers;

  /// Reads the record layout, the screen and K from `uniforms` (technique_params.h); works on the
  /// caller's buffers `b`, which it does not own.
  ArraysKernel(const KernelUniforms& uniforms, const Buffers& b)
      : KernelUniforms(uniforms), b_(b) {}


  /// Increments the pixel's counter; returns the old count (it keeps counting past K).
  uint fa_count_add(uint pixel) {
    if constexpr (Concurrent) return std::atomic_ref<std::uint32_t>(b_.counts[pixel]).fetch_add(1, std::memory_order_relaxed);
    return b_.counts[pixel]++;
  }
  /// The pixel's counter: fragments arrived, or after the sort its sorted length.
  uint fa_load_count(uint pixel) const { return b_.counts[pixel]; }
  /// Sets the pixel's counter to n.
  void fa_store_count(uint pixel, uint n) { b_.counts[pixel] = n; }
  /// The (code, data) entry of layer slot `slot` (layer k of a pixel: k * pixels + pixel).
  uvec2 fa_load_layer(uint slot) const { return b_.layers[slot]; }
  /// Writes entry e to layer slot `slot`.
  void fa_store_layer(uint slot, uvec2 e) { b_.layers[slot] = e; }
  /// Atomic even for one inserter: the sort pass runs its rows on several threads.
  void fa_note_overflow(uint arrived) { ha_fetch_max<true>(*b_.max_arrived, arrived); }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_entries.glsl"
#include "habuffer/techniques/arrays/arrays.glsl"

 private:
  Buffers b_;
};

}  // namespace habuffer
