// The HA-buffer's environment on the GPU, common to its atomic modes: the
// max-age table and the offsets (hash_kernel.h holds them as members on the
// C++ path), and the slot-write tally the mode's atomics raise.

// Slot writes of the current insert call (the atomics raise it).
uint ha_call_writes = 0u;

layout(std430, binding = HABUFFER_BINDING_MAX_AGE) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = HABUFFER_BINDING_OFFSETS) readonly buffer HaOffsets { uvec2 ha_offsets[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }
// Max ages only grow in a gather: a cell read at or above `age` (a stale
// read is a lower bound) needs no atomic (most slot writes of a deep pixel
// find its cell raised already).
void ha_atomic_max_age(uint cell, uint age) {
  if (ha_max_ages[cell] < age) atomicMax(ha_max_ages[cell], age);
}
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
