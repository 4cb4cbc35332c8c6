// The HA-buffer's environment on the GPU, common to its atomic modes: the
// max-age table and the offsets (hash_kernel.h holds them as members on the
// C++ path), and the slot-write tally the mode's atomics raise.

// Slot writes of the current insert call (the atomics raise it in the
// HABUFFER_COUNT_WRITES variant).
uint ha_call_writes = 0u;

// The mode's prelude declares the records (ha_table) at this point.
#define HABUFFER_RECORDS_BINDING HABUFFER_BINDING_TABLE

// HABUFFER_MAX_AGE_READ_FIRST 1: read a max-age cell before raising it
// (ModuleVariant::max_age_read_first); 0, the default: one atomicMax.
#ifndef HABUFFER_MAX_AGE_READ_FIRST
#define HABUFFER_MAX_AGE_READ_FIRST 0
#endif

layout(std430, binding = HABUFFER_BINDING_MAX_AGE) buffer HaMaxAge { uint ha_max_ages[]; };
layout(std430, binding = HABUFFER_BINDING_OFFSETS) readonly buffer HaOffsets { uvec2 ha_offsets[]; };

uvec2 ha_offset(uint i) { return ha_offsets[i]; }
uint ha_div_block(uint v) { return v / ha_block; }
// Max ages only grow in a gather: a cell read at or above `age` (a stale
// read is a lower bound) needs no atomic (most slot writes of a deep pixel
// find its cell raised already). Without the read, the atomic's result is
// unused, so a GPU can issue it as a reduction and go on without waiting.
void ha_atomic_max_age(uint cell, uint age) {
#if HABUFFER_MAX_AGE_READ_FIRST
  if (ha_max_ages[cell] < age) atomicMax(ha_max_ages[cell], age);
#else
  atomicMax(ha_max_ages[cell], age);
#endif
}
uint ha_load_max_age(uint cell) { return ha_max_ages[cell]; }
