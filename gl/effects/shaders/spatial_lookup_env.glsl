// The spatial hash's environment in a host shader (spatial_lookup_part):
// GlSpatialHash's table, max-age cells and offsets, read-only at the points
// HABUFFER_SPATIAL_BINDING_TABLE, _MAX_AGE (the miss filter's words after
// the cells) and _OFFSETS, and its block
// HabufferSpatial (spatial_block.glsl) at _PARAMS. The shared probe and
// lookup follow under the prefix sh_ (ha_probe as sh_probe, ...), beside a
// technique module's own ha_ instance. Slots are read as uvec2 (low, high
// words of the 64-bit record): no 64-bit integers needed, in any mode.
layout(std430, binding = HABUFFER_SPATIAL_BINDING_TABLE) readonly buffer HabufferSpatialTable { uvec2 sh_slots[]; };
layout(std430, binding = HABUFFER_SPATIAL_BINDING_MAX_AGE) readonly buffer HabufferSpatialMaxAge { uint sh_max_age_cells[]; };
layout(std430, binding = HABUFFER_SPATIAL_BINDING_OFFSETS) readonly buffer HabufferSpatialOffsets { uvec2 sh_offsets[]; };

#define HABUFFER_SH_LOOKUP_ONLY
#ifndef HABUFFER_INOUT
#define HABUFFER_INOUT(T) inout T
#endif
#define sh_word uvec2
#define sh_index uint
#define sh_age_bits habuffer_spatial.age_bits
#define sh_table_size habuffer_spatial.table_size
#define sh_quotient_x habuffer_spatial.quotient_x
#define sh_max_age_cells_x habuffer_spatial.max_age_cells_x
#define sh_filter_blocks_x habuffer_spatial.filter_blocks_x
#define sh_filter_shift_y habuffer_spatial.filter_shift_y

uvec2 sh_offset(uint i) { return sh_offsets[i]; }
uint sh_div_block(uint v) { return v / habuffer_spatial.block; }
uint sh_div_hx(uint v) { return v / sh_table_size.x; }
uint sh_div_hy(uint v) { return v / sh_table_size.y; }
sh_word sh_word_of(uint high, uint low) { return uvec2(low, high); }
uint sh_high(sh_word r) { return r.y; }
uint sh_low(sh_word r) { return r.x; }
sh_word sh_load_slot(sh_index s) { return sh_slots[s]; }
uint sh_load_max_age(uint cell) { return sh_max_age_cells[cell]; }
uint sh_load_filter(sh_index w) { return sh_max_age_cells[habuffer_spatial.filter_base + w]; }
