// The part of the GLSL environment every atomic mode shares: the uniforms
// and buffers hash_kernel.h provides as members on the C++ path. A mode's
// prelude (word type, slot storage, slot atomics) comes first.
uniform uint ha_age_bits;
uniform uvec2 ha_table_size;
uniform uint ha_block;
uniform uint ha_max_age_cells_x;
uniform uint ha_iter_limit;
uniform float ha_cull_tau;

layout(std430, binding = 1) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = 2) readonly buffer HaOffsets { uvec2 ha_offsets[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }
void ha_atomic_max_age(uint cell, uint age) { atomicMax(ha_max_ages[cell], age); }
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
