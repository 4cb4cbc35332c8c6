// GLSL environment of the shared HA-buffer sources for L32 records with
// native 32-bit atomics: the same names C++ provides in hash_kernel.h.
#define ha_word uint
#define ha_index uint
#define HA_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint

const uint ha_word_bits = 32u;
const uint ha_payload_bits = 0u;
uniform uint ha_age_bits;
uniform uvec2 ha_table_size;
uniform uvec2 ha_screen_size;
uniform uint ha_block;
uniform uint ha_max_age_cells_x;
uniform uint ha_iter_limit;
uniform float ha_cull_tau;

layout(std430, binding = 0) buffer HaTable { uint ha_table[]; };
layout(std430, binding = 1) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = 2) readonly buffer HaOffsets { uvec2 ha_offsets[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }
ha_word ha_atomic_max_slot(ha_index s, ha_word r) { return atomicMax(ha_table[s], r); }
bool ha_atomic_gave_up() { return false; }
void ha_atomic_max_age(uint cell, uint age) { atomicMax(ha_max_ages[cell], age); }
ha_word ha_load_slot(ha_index s) { return ha_table[s]; }
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
