/// @file
/// The spatial hash's shared GLSL (sh_spatial.glsl) compiled as members of a
/// C++ class, with the table, offsets and max-age cells a shader would get
/// from its buffers: the same construction as HashKernel (hash_kernel.h), so
/// the CPU's table and a GPU's are built by one text.
#pragma once

#include <atomic>
#include <cstdint>

#include "habuffer/extent.h"
#include "habuffer/fast_divisor.h"
#include "habuffer/glsl_env.h"
#include "habuffer/spatial/sh_constants.h"

namespace habuffer::spatial {

static_assert(HABUFFER_SH_MIN_AGE_BITS >= 2u && HABUFFER_SH_MAX_AGE_BITS <= 24u,
              "sh_spatial.glsl packs age, quotient (31 - A bits) and the live bit in 32: keep the age bits in 2..24");
static_assert(HABUFFER_SH_PENDING >= HABUFFER_SH_OUTCOME_COUNT && HABUFFER_SH_CUT >= HABUFFER_SH_OUTCOME_COUNT,
              "HABUFFER_SH_PENDING and HABUFFER_SH_CUT must not collide with an outcome the counters index");

/// The kernel's "uniforms", and the divisors the probe needs made once per
/// table (a FastDivisor costs a 64-bit divide to make: a kernel made per
/// lookup would pay three).
struct SpatialKernelParams {
  SpatialKernelParams(std::uint32_t age_bits_, Extent table_, std::uint32_t quotient_x_, std::uint32_t block_,
                      std::uint32_t iter_limit_, std::uint32_t filter_bits)
      : age_bits(age_bits_),
        table(table_),
        quotient_x(quotient_x_),
        block(block_),
        cells_x((table_.x + block_ - 1) / block_),
        iter_limit(iter_limit_),
        filter_shift_y(filter_shift_y_for(filter_bits)),
        filter_blocks_x(filter_bits != 0u ? blocks(table_.x, HABUFFER_SH_FILTER_SHIFT_X) : 0u),
        filter_words(filter_words_for(table_, filter_bits)),
        div_block(block_),
        div_x(table_.x),
        div_y(table_.y) {}
  std::uint32_t age_bits;    ///< A
  Extent table;              ///< H, in slots
  std::uint32_t quotient_x;  ///< qx = ceil(Du / Hx)
  std::uint32_t block;       ///< the max-age block side
  std::uint32_t cells_x;     ///< max-age cells per row
  std::uint32_t iter_limit;  ///< probes of one insert call
  std::uint32_t filter_shift_y;   ///< log2 of a miss-filter block's height
  std::uint32_t filter_blocks_x;  ///< miss-filter blocks per row (0: no filter)
  std::uint64_t filter_words;     ///< the miss filter's 32-bit words (0: no filter)
  FastDivisor div_block, div_x, div_y;  ///< v / B, v / Hx, v / Hy

  /// Filter blocks along a side of `side` positions, 2^shift a block.
  static std::uint32_t blocks(std::uint32_t side, std::uint32_t shift) {
    return static_cast<std::uint32_t>((std::uint64_t{side} + (1u << shift) - 1u) >> shift);
  }
  /// A block's height (log2) for `bits` bits a position (8 or 16; 512 bits a block).
  static std::uint32_t filter_shift_y_for(std::uint32_t bits) { return bits == 8u ? 3u : 2u; }
  /// The miss filter's 32-bit words for a table of `table` slots at `bits` bits a position (0: none).
  static std::uint64_t filter_words_for(Extent table, std::uint32_t bits) {
    if (bits == 0u) return 0u;
    return std::uint64_t{blocks(table.x, HABUFFER_SH_FILTER_SHIFT_X)} * blocks(table.y, filter_shift_y_for(bits)) *
           HABUFFER_SH_FILTER_WORDS;
  }
};

/// Concurrent: slots and cells updated with atomics (many inserters);
/// otherwise plain loads and stores (one owner).
template <bool Concurrent>
class SpatialHashKernel {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  using sh_word = std::uint64_t;
  /// Slot index: 64 bits (shared/ha_probe.glsl's type).
  using ha_index = std::uint64_t;

  SpatialHashKernel(const SpatialKernelParams& p, const glm::uvec2* offsets, sh_word* table, std::uint32_t* max_age,
                    std::uint32_t* filter)
      : sh_age_bits(p.age_bits),
        ha_table_size(p.table.x, p.table.y),
        sh_quotient_x(p.quotient_x),
        ha_max_age_cells_x(p.cells_x),
        sh_iter_limit(p.iter_limit),
        sh_filter_blocks_x(p.filter_blocks_x),
        sh_filter_shift_y(p.filter_shift_y),
        block_(p.div_block),
        hx_(p.div_x),
        hy_(p.div_y),
        offsets_(offsets),
        table_(table),
        max_age_(max_age),
        filter_(filter) {}

  uint sh_age_bits;
  uvec2 ha_table_size;  ///< H (shared/ha_probe.glsl's name)
  uint sh_quotient_x;
  uint ha_max_age_cells_x;
  uint sh_iter_limit;
  uint sh_filter_blocks_x;
  uint sh_filter_shift_y;

  uvec2 ha_offset(uint i) const { return offsets_[i]; }
  uint ha_div_block(uint v) const { return block_.div(v); }
  uint sh_div_hx(uint v) const { return hx_.div(v); }
  uint sh_div_hy(uint v) const { return hy_.div(v); }
  static sh_word sh_word_of(uint high, uint low) { return (sh_word{high} << 32) | low; }
  static uint sh_high(sh_word r) { return static_cast<uint>(r >> 32); }
  static uint sh_low(sh_word r) { return static_cast<uint>(r); }
  sh_word sh_atomic_max_slot(ha_index s, sh_word r) { return ha_fetch_max<Concurrent>(table_[s], r); }
  /// CPU atomics always happen.
  static uint sh_atomic_missed() { return 0u; }
  sh_word sh_load_slot(ha_index s) const { return ha_fetch<Concurrent>(table_[s]); }
  void sh_atomic_max_age(uint cell, uint age) {
    if (ha_fetch<Concurrent>(max_age_[cell]) < age) ha_fetch_max<Concurrent>(max_age_[cell], age);
  }
  uint sh_load_max_age(uint cell) const { return ha_fetch<Concurrent>(max_age_[cell]); }
  uint sh_load_filter(ha_index w) const { return ha_fetch<Concurrent>(filter_[w]); }
  /// GLSL's atomicOr, skipped when the bits are already set.
  void sh_atomic_or_filter(ha_index w, uint bits) {
    if constexpr (Concurrent) {
      std::atomic_ref<std::uint32_t> a(filter_[w]);
      if ((a.load(std::memory_order_relaxed) & bits) != bits) a.fetch_or(bits, std::memory_order_relaxed);
    } else {
      filter_[w] |= bits;
    }
  }

#include "habuffer/shared/ha_probe.glsl"
#include "habuffer/spatial/sh_spatial.glsl"

 private:
  FastDivisor block_, hx_, hy_;
  const glm::uvec2* offsets_;
  sh_word* table_;
  std::uint32_t* max_age_;
  std::uint32_t* filter_;
};

}  // namespace habuffer::spatial
