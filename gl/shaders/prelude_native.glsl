// Atomic modes native32 (L32, atomicMax on uint slots) and native64 (L64,
// atomicMax on uint64_t slots with GL_NV_shader_atomic_int64): the module
// assembly defines ha_word for the mode and enables its extensions.
layout(std430, binding = HA_BINDING_TABLE) coherent buffer HaTable { ha_word ha_table[]; };
#if HA_WORD_BITS == 64
// The same table as 32-bit words (little-endian: word 2s + 1 is slot s's
// high half), for the one-load check of ha_slot_high.
layout(std430, binding = HA_BINDING_TABLE) coherent buffer HaTableWords { uint ha_table_words[]; };
uint ha_slot_high(ha_index s) { return ha_table_words[2u * s + 1u]; }
#else
uint ha_slot_high(ha_index s) { return ha_table[s]; }
#endif

ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = atomicMax(ha_table[s], r);
  if (old < r) ha_call_writes += 1u;
  return old;
}
uint ha_atomic_missed() { return 0u; }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
