// Atomic modes native32 (L32, atomicMax on uint slots) and native64 (L64,
// atomicMax on uint64_t slots with GL_NV_shader_atomic_int64): the module
// assembly defines ha_word for the mode and enables its extensions.
// Plain reads may be stale: slots only grow in a gather, so a stale value
// is a lower bound, which is all the read-first checks rely on.
layout(std430, binding = HABUFFER_RECORDS_BINDING) buffer HaTable { ha_word ha_table[]; };

ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = atomicMax(ha_table[s], r);
#ifdef HABUFFER_COUNT_WRITES
  if (old < r) ha_call_writes += 1u;
#endif
  return old;
}
uint ha_atomic_missed() { return 0u; }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
