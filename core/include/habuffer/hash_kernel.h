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
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;
  std::uint32_t payload_bits = 32;  ///< 32 for L64, 0 for L32
  Extent table;
  std::uint32_t block = HABUFFER_DEFAULT_BLOCK;
  std::uint32_t max_age_cells_x = 0;
  std::uint32_t iter_limit = HABUFFER_DEFAULT_ITER_LIMIT;
  float cull_tau = 0.0f;  ///< 0: early cull off
  Extent screen;
  std::uint32_t* saturation = nullptr;  ///< early cull with saturation: a code per pixel (else nullptr: off)
};

/// Word: std::uint64_t (L64) or std::uint32_t (L32). Concurrent: slots and
/// max-age cells are updated with atomics (several inserters at once); the
/// serial form uses plain loads and stores and must own the table alone.
template <class Word, bool Concurrent>
class HashKernel {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  using ha_word = Word;
  using ha_index = std::uint64_t;

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
  static constexpr uint ha_word_bits = sizeof(Word) * 8;
  uint ha_age_bits;
  uint ha_payload_bits;
  uvec2 ha_table_size;
  uint ha_block;
  uint ha_max_age_cells_x;
  uint ha_iter_limit;
  float ha_cull_tau;
  uvec2 ha_screen_size;
  uint ha_saturation;

  uvec2 ha_offset(uint i) const { return offsets_[i]; }

  /// v / B by multiplication: a hardware divide per placement costs more than the probe.
  uint ha_div_block(uint v) const { return block_.div(v); }

  Word ha_atomic_max_slot(ha_index s, Word r) { return ha_fetch_max<Concurrent>(table_[s], r); }
  /// CPU atomics always happen (the compare-exchange loop is lock-free).
  static uint ha_atomic_missed() { return 0u; }
  void ha_atomic_max_age(uint cell, uint age) { ha_fetch_max<Concurrent>(max_age_[cell], age); }
  Word ha_load_slot(ha_index s) const { return ha_fetch<Concurrent>(table_[s]); }
  uint ha_load_max_age(uint cell) const { return ha_fetch<Concurrent>(max_age_[cell]); }
  uint ha_load_saturation(uint pixel) const { return ha_fetch<Concurrent>(saturation_[pixel]); }
  void ha_max_saturation(uint pixel, uint code) { ha_fetch_max<Concurrent>(saturation_[pixel], code); }

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
