/// @file
/// The k-buffer on the CPU: the shared GLSL of techniques/kbuffer/cpu/include/habuffer/techniques/kbuffer/kbuffer.glsl
/// compiled as member functions over the buffers a shader would get.
#pragma once

#include <atomic>
#include <bit>
#include <cstdint>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The buffers a kernel works on (what a shader gets bound); Word: std::uint64_t
/// (L64) or std::uint32_t (L32).
template <class Word>
struct KBufferBuffers {
  Word* slots;               ///< K per pixel, layer-major
  std::uint32_t* occupancy;  ///< occupancy_words per pixel (occupancy on)
  std::uint32_t* limits;     ///< one bucket per pixel (occupancy on)
};

/// Concurrent: slots and occupancy bits are updated atomically (several
/// inserters at once); the count pass and compositing need none.
template <class Word, bool Concurrent>
class KBufferKernel : public KernelUniforms {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The slot word.
  using ha_word = Word;
  /// Slot index: 64 bits.
  using ha_index = std::uint64_t;
  static constexpr uint ha_word_bits = sizeof(Word) * 8;  ///< bits of Word

  /// Reads the record layout, the screen, K and the occupancy geometry from
  /// `params`; works on the caller's buffers `b`, which it does not own.
  KBufferKernel(const KernelUniforms& uniforms, const KBufferBuffers<Word>& b)
      : KernelUniforms(uniforms), b_(b) {}


  /// atomicMax on slot s: returns the old value, leaves max(old, r).
  Word ha_atomic_max_slot(ha_index s, Word r) { return ha_fetch_max<Concurrent>(b_.slots[s], r); }
  /// CPU atomics always happen: always 0.
  static uint ha_atomic_missed() { return 0u; }
  /// Slot s (a relaxed atomic read when Concurrent).
  Word ha_load_slot(ha_index s) const { return ha_fetch<Concurrent>(b_.slots[s]); }
  /// Sets `bits` in occupancy word `word` (an atomic or when Concurrent and not all set yet).
  void kb_or_occupancy(uint word, uint bits) {
    if constexpr (Concurrent) {
      std::atomic_ref<std::uint32_t> w(b_.occupancy[word]);
      if ((w.load(std::memory_order_relaxed) & bits) != bits) w.fetch_or(bits, std::memory_order_relaxed);
    } else {
      b_.occupancy[word] |= bits;
    }
  }
  /// Occupancy word `word`.
  uint kb_load_occupancy(uint word) const { return b_.occupancy[word]; }
  /// The pixel's limit bucket.
  uint kb_load_limit(uint pixel) const { return b_.limits[pixel]; }
  /// Sets the pixel's limit bucket.
  void kb_store_limit(uint pixel, uint bucket) { b_.limits[pixel] = bucket; }
  /// Index of the lowest set bit of a non-zero word.
  static uint ha_lowest_bit(uint w) { return static_cast<uint>(std::countr_zero(w)); }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_carry.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/techniques/kbuffer/kbuffer.glsl"

 private:
  KBufferBuffers<Word> b_;
};

}  // namespace habuffer
