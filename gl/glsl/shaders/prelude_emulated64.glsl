// Atomic mode emulated64: L64 records on drivers with 64-bit types but no
// 64-bit atomics (Mesa llvmpipe); atomicMax on a 64-bit slot is emulated with
// a 32-bit lock per 2^HABUFFER_LOCK_SHIFT slots (the module assembly defines ha_word as uint64_t and
// enables GL_ARB_gpu_shader_int64).
// The fence between writes and the atomic that publishes them. A module
// assembly may define it first: the Vulkan path defines it empty on
// lavapipe (vk::vulkan_device_defines says why).
#ifndef HABUFFER_BUFFER_FENCE
#define HABUFFER_BUFFER_FENCE() memoryBarrierBuffer()
#endif
layout(std430, binding = HABUFFER_RECORDS_BINDING) coherent buffer HaTable { uint64_t ha_table[]; };
layout(std430, binding = HABUFFER_BINDING_LOCKS) coherent buffer HaLocks { uint ha_locks[]; };


// One attempt at the slot's lock; on success the max is done and `old` set.
// The lock is taken and released inside this one call, so lanes of one SIMD
// group that contend for the same slot cannot deadlock: the lane that wins
// runs its critical section while the others try again.
bool ha_try_max_slot(ha_index s, ha_word r, inout ha_word old) {
  uint lock = s >> HABUFFER_LOCK_SHIFT;
  if (atomicCompSwap(ha_locks[lock], 0u, 1u) != 0u) return false;
  HABUFFER_BUFFER_FENCE();
  old = ha_table[s];
  if (old < r) {
    ha_table[s] = r;
#ifdef HABUFFER_COUNT_WRITES
    ha_call_writes += 1u;
#endif
  }
  HABUFFER_BUFFER_FENCE();
  atomicExchange(ha_locks[lock], 0u);
  return true;
}

// Consecutive attempts that found the slot locked, and what the last one
// means for the insert step (read right after the atomic, ha_atomic_missed).
uint ha_busy_attempts = 0u;
uint ha_missed = 0u;
uint ha_atomic_missed() { return ha_missed; }

// One attempt per call, no loop of its own: a busy slot makes the insert step
// return HABUFFER_PENDING with its carry unchanged, so the step's own loop is the
// spin. That keeps the insertion a single loop, whose back edge is the only
// place a driver's loop budget can stop it (llvmpipe gives an invocation about
// 65535 iterations in all): a nested spin loop stopped there was seen to leave
// lanes whose write had happened looking as if it had not. After
// habuffer_lock_spin_limit busy attempts in a row the call is cut short (HABUFFER_CUT) and
// the frame's resume pass goes on with it.
ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = ha_word(0);
  if (ha_try_max_slot(s, r, old)) {
    ha_busy_attempts = 0u;
    ha_missed = 0u;
    return old;
  }
  ha_busy_attempts += 1u;
  ha_missed = ha_busy_attempts >= habuffer_lock_spin_limit ? HABUFFER_CUT : HABUFFER_PENDING;
  if (ha_missed == HABUFFER_CUT) ha_busy_attempts = 0u;
  return ha_word(0);
}
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
