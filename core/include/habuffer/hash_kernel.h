/// @file
/// The coherent Robin Hood hash on the CPU: the shared GLSL sources of
/// core/include/habuffer/shared/ compiled as member functions of this class template, with the
/// storage and atomics a GLSL shader would get from its buffers.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/glsl_env.h"
#include "habuffer/fast_divisor.h"

namespace habuffer {

/// Everything a kernel reads besides its buffers: the GLSL "uniforms".
struct KernelParams {
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< A (SPEC 2)
  std::uint32_t payload_bits = 32;  ///< 32 for L64, 0 for L32
  Extent table;  ///< H, in slots
  std::uint32_t block = HABUFFER_DEFAULT_BLOCK;  ///< B, the max-age block side in pixels (SPEC 5)
  std::uint32_t max_age_cells_x = 0;  ///< max-age cells per row
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;  ///< LIMIT of SPEC 6: iterations of one insert call
  float cull_tau = 0.0f;  ///< 0: early cull off
  Extent screen;  ///< V, in pixels
  std::uint32_t* saturation = nullptr;  ///< early cull with saturation: a code per pixel (else nullptr: off)
};

/// Word: std::uint64_t (L64) or std::uint32_t (L32). Concurrent: slots and
/// max-age cells are updated with atomics (several inserters at once); the
/// serial form uses plain loads and stores and must own the table alone.
template <class Word, bool Concurrent>
class HashKernel {
 public:
  /// GLSL's types and builtins (glsl_env.h).
  HABUFFER_GLSL_CLASS_PRELUDE
  /// The slot word.
  using ha_word = Word;
  /// Slot index: 64 bits, so tables above 2^32 slots work.
  using ha_index = std::uint64_t;

  /// Works on the caller's offsets (AMAX of them), table slots and max-age cells
  /// (and params.saturation's image when set); it owns none of them.
  HashKernel(const KernelParams& params, const glm::uvec2* offsets, Word* table, std::uint32_t* max_age)
      : ha_age_bits(params.age_bits),
        ha_payload_bits(params.payload_bits),
        ha_table_size(params.table.x, params.table.y),
        ha_block(params.block),
        ha_max_age_cells_x(params.max_age_cells_x),
        ha_iter_limit(params.iter_limit),
        ha_cull_tau(params.cull_tau),
        ha_screen_size(params.screen.x, params.screen.y),
        ha_saturation(params.saturation != nullptr ? 1u : 0u),
        block_(params.block),
        saturation_(params.saturation),
        offsets_(offsets),
        table_(table),
        max_age_(max_age) {}

  /// --- the environment the shared GLSL expects -----------------------------
  static constexpr uint ha_word_bits = sizeof(Word) * 8;  ///< bits of Word
  uint ha_age_bits;  ///< A
  uint ha_payload_bits;  ///< 32 for L64, 0 for L32
  uvec2 ha_table_size;  ///< H
  uint ha_block;  ///< B
  uint ha_max_age_cells_x;  ///< max-age cells per row
  uint ha_iter_limit;  ///< LIMIT of SPEC 6
  float ha_cull_tau;  ///< 0: early cull off
  uvec2 ha_screen_size;  ///< V
  uint ha_saturation;  ///< 1: saturation depth on, 0: off

  /// O[i] (SPEC 3).
  uvec2 ha_offset(uint i) const { return offsets_[i]; }

  /// v / B by multiplication: a hardware divide per placement costs more than the probe.
  uint ha_div_block(uint v) const { return block_.div(v); }

  /// atomicMax on slot s: returns the old value, leaves max(old, r).
  Word ha_atomic_max_slot(ha_index s, Word r) { return ha_fetch_max<Concurrent>(table_[s], r); }
  /// CPU atomics always happen (the compare-exchange loop is lock-free).
  static uint ha_atomic_missed() { return 0u; }
  /// Raises max-age cell `cell` to at least `age` (atomic max).
  void ha_atomic_max_age(uint cell, uint age) { ha_fetch_max<Concurrent>(max_age_[cell], age); }
  /// Slot s (a relaxed atomic read when Concurrent).
  Word ha_load_slot(ha_index s) const { return ha_fetch<Concurrent>(table_[s]); }
  /// Max-age cell `cell` (a relaxed atomic read when Concurrent).
  uint ha_load_max_age(uint cell) const { return ha_fetch<Concurrent>(max_age_[cell]); }
  /// The pixel's saturation code (saturation on only).
  uint ha_load_saturation(uint pixel) const { return ha_fetch<Concurrent>(saturation_[pixel]); }
  /// Raises the pixel's saturation code to at least `code` (atomic max).
  void ha_max_saturation(uint pixel, uint code) { ha_fetch_max<Concurrent>(saturation_[pixel], code); }

  /// The table's slots.
  [[nodiscard]] const Word* slots() const { return table_; }

  /// --- the shared algorithm -------------------------------------------------
#include "shared/ha_record.glsl"
#include "shared/ha_probe.glsl"
#include "shared/ha_carry.glsl"
#include "shared/ha_saturation.glsl"
#include "shared/ha_insert.glsl"
#include "shared/ha_blend.glsl"
#include "shared/ha_traverse.glsl"

 private:
  FastDivisor block_;
  std::uint32_t* saturation_;
  const glm::uvec2* offsets_;
  Word* table_;
  std::uint32_t* max_age_;
};

}  // namespace habuffer
