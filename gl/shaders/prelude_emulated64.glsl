// Atomic mode emulated64: L64 records on drivers with 64-bit types but no
// 64-bit atomics (Mesa llvmpipe); atomicMax on a 64-bit slot is emulated with
// a per-slot 32-bit lock.
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

layout(std430, binding = 0) coherent buffer HaTable { uint64_t ha_table[]; };
layout(std430, binding = 5) coherent buffer HaLocks { uint ha_locks[]; };

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
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
