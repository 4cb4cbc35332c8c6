/// @file
/// The spatial hash's shared GLSL (sh_spatial.glsl) compiled as members of a
/// C++ class, with the table, offsets and max-age cells a shader would get
/// from its buffers: the same construction as HashKernel (hash_kernel.h), so
/// the CPU's table and a GPU's are built by one text.
#pragma once

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
                      std::uint32_t iter_limit_)
      : age_bits(age_bits_),
        table(table_),
        quotient_x(quotient_x_),
        block(block_),
        cells_x((table_.x + block_ - 1) / block_),
        iter_limit(iter_limit_),
        div_block(block_),
        div_x(table_.x),
        div_y(table_.y) {}
  std::uint32_t age_bits;    ///< A
  Extent table;              ///< H, in slots
  std::uint32_t quotient_x;  ///< qx = ceil(Du / Hx)
  std::uint32_t block;       ///< the max-age block side
  std::uint32_t cells_x;     ///< max-age cells per row
  std::uint32_t iter_limit;  ///< probes of one insert call
  FastDivisor div_block, div_x, div_y;  ///< v / B, v / Hx, v / Hy
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

  SpatialHashKernel(const SpatialKernelParams& p, const glm::uvec2* offsets, sh_word* table, std::uint32_t* max_age)
      : sh_age_bits(p.age_bits),
        ha_table_size(p.table.x, p.table.y),
        sh_quotient_x(p.quotient_x),
        ha_max_age_cells_x(p.cells_x),
        sh_iter_limit(p.iter_limit),
        block_(p.div_block),
        hx_(p.div_x),
        hy_(p.div_y),
        offsets_(offsets),
        table_(table),
        max_age_(max_age) {}

  uint sh_age_bits;
  uvec2 ha_table_size;  ///< H (shared/ha_probe.glsl's name)
  uint sh_quotient_x;
  uint ha_max_age_cells_x;
  uint sh_iter_limit;

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

#include "habuffer/shared/ha_probe.glsl"
#include "habuffer/spatial/sh_spatial.glsl"

 private:
  FastDivisor block_, hx_, hy_;
  const glm::uvec2* offsets_;
  sh_word* table_;
  std::uint32_t* max_age_;
};

}  // namespace habuffer::spatial
