// The spatial hash's environment on the GPU (what core/include/habuffer/
// spatial/sh_spatial.glsl expects from its host; the C++ host is
// SpatialHashKernel). Slots are uint64_t (GL_ARB_gpu_shader_int64); with
// HABUFFER_SH_NATIVE64 their atomicMax is native (GL_NV_shader_atomic_int64), else it
// is emulated with a 32-bit lock per 8 slots (Mesa llvmpipe), one attempt
// per call: a busy lock makes the step return HABUFFER_SH_PENDING with its carry
// unchanged, so the step's own loop is the spin, and after sh_lock_spin_limit
// busy attempts the call is cut short (HABUFFER_SH_CUT) and resumed by the next pass.
#define sh_word uint64_t
#define ha_index uint
#define HABUFFER_INOUT(T) inout T

uniform uint sh_age_bits;
uniform uvec2 ha_table_size;
uniform uint sh_quotient_x;
uniform uint ha_max_age_cells_x;
uniform uint sh_iter_limit;
uniform uint sh_block;
uniform uint sh_lock_spin_limit;

layout(std430, binding = HABUFFER_BINDING_TABLE) coherent buffer ShTable { uint64_t sh_table[]; };
layout(std430, binding = HABUFFER_BINDING_MAX_AGE) coherent buffer ShMaxAge { uint sh_max_age_cells[]; };
layout(std430, binding = HABUFFER_BINDING_OFFSETS) readonly buffer ShOffsets { uvec2 sh_offsets[]; };
layout(std430, binding = HABUFFER_BINDING_LOCKS) coherent buffer ShLocks { uint sh_locks[]; };

uvec2 ha_offset(uint i) { return sh_offsets[i]; }
uint ha_div_block(uint v) { return v / sh_block; }
uint sh_div_hx(uint v) { return v / ha_table_size.x; }
uint sh_div_hy(uint v) { return v / ha_table_size.y; }
sh_word sh_word_of(uint high, uint low) { return packUint2x32(uvec2(low, high)); }
uint sh_high(sh_word r) { return unpackUint2x32(r).y; }
uint sh_low(sh_word r) { return unpackUint2x32(r).x; }
sh_word sh_load_slot(ha_index s) { return sh_table[s]; }
void sh_atomic_max_age(uint cell, uint a) {
  if (sh_max_age_cells[cell] < a) atomicMax(sh_max_age_cells[cell], a);
}
uint sh_load_max_age(uint cell) { return sh_max_age_cells[cell]; }

#ifdef HABUFFER_SH_NATIVE64
sh_word sh_atomic_max_slot(ha_index s, sh_word r) { return atomicMax(sh_table[s], r); }
uint sh_atomic_missed() { return 0u; }
#else
uint sh_busy_attempts = 0u;
uint sh_missed = 0u;
uint sh_atomic_missed() { return sh_missed; }
sh_word sh_atomic_max_slot(ha_index s, sh_word r) {
  uint lock = s >> 3u;
  if (atomicCompSwap(sh_locks[lock], 0u, 1u) == 0u) {
    memoryBarrierBuffer();
    sh_word old = sh_table[s];
    if (old < r) sh_table[s] = r;
    memoryBarrierBuffer();
    atomicExchange(sh_locks[lock], 0u);
    sh_busy_attempts = 0u;
    sh_missed = 0u;
    return old;
  }
  sh_busy_attempts += 1u;
  sh_missed = sh_busy_attempts >= sh_lock_spin_limit ? HABUFFER_SH_CUT : HABUFFER_SH_PENDING;
  if (sh_missed == HABUFFER_SH_CUT) sh_busy_attempts = 0u;
  return sh_word(0);
}
#endif
