// GLSL environment of the shared HA-buffer sources for L64 records on
// drivers with 64-bit types but no 64-bit atomics (Mesa llvmpipe): atomicMax
// on a 64-bit slot is emulated with a per-slot 32-bit lock.
#extension GL_ARB_gpu_shader_int64 : require
#define ha_word uint64_t
#define ha_index uint
#define HA_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint
// Attempts at a contended lock before the insert call gives up (failed_iter).
#define HA_LOCK_SPIN_LIMIT 1000000u

const uint ha_word_bits = 64u;
const uint ha_payload_bits = 32u;
uniform uint ha_age_bits;
uniform uvec2 ha_table_size;
uniform uvec2 ha_screen_size;
uniform uint ha_block;
uniform uint ha_max_age_cells_x;
uniform uint ha_iter_limit;
uniform float ha_cull_tau;

layout(std430, binding = 0) coherent buffer HaTable { uint64_t ha_table[]; };
layout(std430, binding = 1) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = 2) readonly buffer HaOffsets { uvec2 ha_offsets[]; };
layout(std430, binding = 5) coherent buffer HaLocks { uint ha_locks[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }

bool ha_gave_up = false;
bool ha_atomic_gave_up() { return ha_gave_up; }

// The lock is taken and released inside one iteration of the loop, so lanes
// of one SIMD group that contend for the same slot cannot deadlock: the lane
// that wins runs its critical section while the others retry.
ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  for (uint spin = 0u; spin < HA_LOCK_SPIN_LIMIT; ++spin) {
    if (atomicCompSwap(ha_locks[s], 0u, 1u) == 0u) {
      memoryBarrierBuffer();
      ha_word old = ha_table[s];
      if (old < r) ha_table[s] = r;
      memoryBarrierBuffer();
      atomicExchange(ha_locks[s], 0u);
      return old;
    }
  }
  ha_gave_up = true;
  return ha_word(0);
}
void ha_atomic_max_age(uint cell, uint age) { atomicMax(ha_max_ages[cell], age); }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
