// Atomic mode emulated64: L64 records on drivers with 64-bit types but no
// 64-bit atomics (Mesa llvmpipe); atomicMax on a 64-bit slot is emulated with
// a per-slot 32-bit lock (the module assembly defines ha_word as uint64_t and
// enables GL_ARB_gpu_shader_int64).
layout(std430, binding = HA_BINDING_TABLE) coherent buffer HaTable { uint64_t ha_table[]; };
layout(std430, binding = HA_BINDING_LOCKS) coherent buffer HaLocks { uint ha_locks[]; };

// Set by a slot atomic that gave up; read (and reset) right after that atomic,
// so one invocation inserting many fragments fails only the call concerned.
bool ha_gave_up = false;
bool ha_atomic_gave_up() {
  bool gave_up = ha_gave_up;
  ha_gave_up = false;
  return gave_up;
}

// One attempt at the slot's lock; on success the max is done and `old` set.
// The lock is taken and released inside this one call, so lanes of one SIMD
// group that contend for the same slot cannot deadlock: the lane that wins
// runs its critical section while the others retry.
bool ha_try_max_slot(ha_index s, ha_word r, inout ha_word old) {
  if (atomicCompSwap(ha_locks[s], 0u, 1u) != 0u) return false;
  memoryBarrierBuffer();
  old = ha_table[s];
  if (old < r) {
    ha_table[s] = r;
    ha_call_writes += 1u;
  }
  memoryBarrierBuffer();
  atomicExchange(ha_locks[s], 0u);
  return true;
}

// Bounded spinning: up to ha_lock_spin_limit attempts, then the insert call
// gives up (failed_iter, and cut short: lossless mode gathers it again into
// the same table). One attempt per iteration: unrolling the attempts halves
// llvmpipe's speed, and no unrolling outlasts a lock holder the OS preempted
// (llvmpipe gives a shader invocation about 65535 loop iterations in all).
ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = ha_word(0);
  for (uint spin = 0u; spin < ha_lock_spin_limit; ++spin)
    if (ha_try_max_slot(s, r, old)) return old;
  ha_gave_up = true;
  ha_call_cut = true;
  return ha_word(0);
}
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
