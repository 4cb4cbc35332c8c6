// The part of the GLSL environment every atomic mode shares (the module
// assembly has defined ha_word, ha_word_bits and ha_payload_bits): the parameters
// hash_kernel.h holds as members on the C++ path (here one uniform block, so
// a host shader needs no uniforms of ours, only our buffers bound), the
// max-age table and the offsets. The HA_BINDING_* points are #defined before
// this file by the module assembly (GlBindings), so hosts choose them.
layout(std140, binding = HA_BINDING_PARAMS) uniform HaParams {
  uvec2 ha_table_size;
  uint ha_age_bits;
  uint ha_block;
  uint ha_max_age_cells_x;
  uint ha_iter_limit;
  float ha_cull_tau;
  uint ha_lock_spin_limit;
  uvec2 ha_screen_size;
  uint ha_capture_capacity;  // fragments the capture buffer holds; 0: capture off
  uint ha_capture_only;  // 1: capture, insert nothing, count nothing
  uint ha_count_writes;  // 1: count slot writes (HA_COUNTER_SLOT_WRITES)
  uint ha_deferred_capacity;  // calls cut short that the deferred-call buffer holds
  uint ha_params_pad1;
  uint ha_params_pad2;
};

#define ha_index uint
#define HA_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint

// Slot writes of the current insert call (the atomics raise it).
uint ha_call_writes = 0u;

layout(std430, binding = HA_BINDING_MAX_AGE) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = HA_BINDING_OFFSETS) readonly buffer HaOffsets { uvec2 ha_offsets[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }
void ha_atomic_max_age(uint cell, uint age) { atomicMax(ha_max_ages[cell], age); }
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
