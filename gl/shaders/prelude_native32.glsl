// Atomic mode native32: L32 records, atomicMax on uint slots.
#define ha_word uint
#define ha_index uint
#define HA_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint

const uint ha_word_bits = 32u;
const uint ha_payload_bits = 0u;

layout(std430, binding = HA_BINDING_TABLE) buffer HaTable { uint ha_table[]; };

ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = atomicMax(ha_table[s], r);
  if (old < r) ha_call_writes += 1u;
  return old;
}
bool ha_atomic_gave_up() { return false; }
// Whether the current insert call was cut short (a lock given up, or the
// driver's loop budget spent) rather than failed by the table: the entry
// counts those apart, so lossless mode gathers them again without growing it.
bool ha_call_cut = false;
void ha_begin_call() { ha_call_cut = false; }
bool ha_call_cut_short() { return ha_call_cut; }
void ha_loop_cut() { ha_call_cut = true; }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
