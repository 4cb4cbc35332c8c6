// Atomic mode native64: L64 records, atomicMax on uint64_t slots
// (GL_NV_shader_atomic_int64, as on NVIDIA GPUs; the module assembly enables
// it and GL_ARB_gpu_shader_int64).
#define ha_word uint64_t
#define ha_index uint
#define HA_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint

const uint ha_word_bits = 64u;
const uint ha_payload_bits = 32u;

layout(std430, binding = HA_BINDING_TABLE) buffer HaTable { uint64_t ha_table[]; };

ha_word ha_atomic_max_slot(ha_index s, ha_word r) {
  ha_word old = atomicMax(ha_table[s], r);
  if (old < r) ha_call_writes += 1u;
  return old;
}
bool ha_atomic_gave_up() { return false; }
void ha_begin_call() {}
bool ha_call_gave_up() { return false; }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
void ha_store_slot(ha_index s, ha_word r) { ha_table[s] = r; }
