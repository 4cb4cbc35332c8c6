// The spatial hash's environment on the GPU (what core/spatial/include/
// habuffer/spatial/sh_spatial.glsl and shared/ha_probe.glsl expect from their host;
// the C++ host is SpatialHashKernel). Slots are uint64_t
// (GL_ARB_gpu_shader_int64), their atomicMax the HA-buffer's own: the host
// assembles prelude_native.glsl (GL_NV_shader_atomic_int64) or
// prelude_emulated64.glsl (a 32-bit lock per 8 slots, one attempt per step:
// a busy lock makes the step return HABUFFER_SH_PENDING with its carry
// unchanged, so the step's loop is the spin, and after
// habuffer_lock_spin_limit busy attempts the call is cut short,
// HABUFFER_SH_CUT, and resumed by the next pass) before this file, over
// ha_table at HABUFFER_RECORDS_BINDING, and spatial_block.glsl (the table's
// parameters). Buffers at GlBindings' points; the miss filter's words
// follow the max-age cells in theirs (at habuffer_spatial.filter_base).
#define sh_word uint64_t
#define HABUFFER_INOUT(T) inout T

#define sh_age_bits habuffer_spatial.age_bits
#define ha_table_size habuffer_spatial.table_size
#define sh_quotient_x habuffer_spatial.quotient_x
#define ha_max_age_cells_x habuffer_spatial.max_age_cells_x
#define sh_iter_limit habuffer_spatial.iter_limit
#define sh_filter_blocks_x habuffer_spatial.filter_blocks_x
#define sh_filter_shift_y habuffer_spatial.filter_shift_y

layout(std430, binding = HABUFFER_BINDING_MAX_AGE) coherent buffer ShMaxAge { uint sh_max_age_cells[]; };
layout(std430, binding = HABUFFER_BINDING_OFFSETS) readonly buffer ShOffsets { uvec2 sh_offsets[]; };

uvec2 ha_offset(uint i) { return sh_offsets[i]; }
uint ha_div_block(uint v) { return v / habuffer_spatial.block; }
uint sh_div_hx(uint v) { return v / ha_table_size.x; }
uint sh_div_hy(uint v) { return v / ha_table_size.y; }
sh_word sh_word_of(uint high, uint low) { return packUint2x32(uvec2(low, high)); }
uint sh_high(sh_word r) { return unpackUint2x32(r).y; }
uint sh_low(sh_word r) { return unpackUint2x32(r).x; }
sh_word sh_load_slot(ha_index s) { return ha_load_slot(s); }
void sh_atomic_max_age(uint cell, uint a) {
  if (sh_max_age_cells[cell] < a) atomicMax(sh_max_age_cells[cell], a);
}
uint sh_load_max_age(uint cell) { return sh_max_age_cells[cell]; }
// The miss filter's words follow the max-age cells in their buffer.
uint sh_load_filter(ha_index w) { return sh_max_age_cells[habuffer_spatial.filter_base + w]; }
void sh_atomic_or_filter(ha_index w, uint bits) {
  ha_index at = habuffer_spatial.filter_base + w;
  if ((sh_max_age_cells[at] & bits) != bits) atomicOr(sh_max_age_cells[at], bits);
}
sh_word sh_atomic_max_slot(ha_index s, sh_word r) { return ha_atomic_max_slot(s, r); }
// The prelude's "missed" codes in the spatial hash's numbering.
uint sh_atomic_missed() {
  uint m = ha_atomic_missed();
  return m == 0u ? 0u : m == HABUFFER_CUT ? HABUFFER_SH_CUT : HABUFFER_SH_PENDING;
}
