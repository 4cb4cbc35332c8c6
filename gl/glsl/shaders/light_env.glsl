// The light buffer of a translucent shadow map, beside the module's own
// technique (seed 000, section 6): the light's HA-buffer (its table, max-age
// table and offsets at points of their own, GlLightBindings) and its
// parameters in a block of their own, read by the shared record, probe,
// blend and traversal sources instantiated with the prefix hs_
// (light_lookup_part). The light buffer's records are L64: a colour with
// its opacity.
layout(std430, binding = HABUFFER_LIGHT_BINDING_TABLE) readonly buffer HsTable { uint64_t hs_table[]; };
layout(std430, binding = HABUFFER_LIGHT_BINDING_MAX_AGE) readonly buffer HsMaxAge { uint hs_max_ages[]; };
layout(std430, binding = HABUFFER_LIGHT_BINDING_OFFSETS) readonly buffer HsOffsets { uvec2 hs_offsets[]; };
layout(std140, binding = HABUFFER_LIGHT_BINDING_PARAMS) uniform HabufferLight {
  mat4 view;             // world to the light's eye space
  mat4 projection;       // the light's eye space to clip space
  uvec2 table_size;      // the light buffer's table H
  uvec2 map_size;        // the light map's pixels (the light buffer's screen)
  uint age_bits;         // its records' age bits A
  uint block;            // its max-age block B
  uint max_age_cells_x;  // its max-age cells per row
  uint bias;             // the receiver's bias in depth codes (transmittance.h)
  float near_plane;      // eye distances that map to t = 0 and t = 1
  float far_plane;
} habuffer_light;

#define hs_word uint64_t
#define hs_index uint
#define hs_word_bits 64u
#define hs_payload_bits 32u
#define hs_age_bits habuffer_light.age_bits
#define hs_coverage_bits 0u  // light buffers are never multisampled
#define hs_table_size habuffer_light.table_size
#define hs_max_age_cells_x habuffer_light.max_age_cells_x
#define hs_floor floor
#define hs_float_bits floatBitsToUint

hs_word hs_load_slot(hs_index s) { return hs_table[s]; }
uint hs_load_max_age(uint cell) { return hs_max_ages[cell]; }
uvec2 hs_offset(uint i) { return hs_offsets[i]; }
uint hs_div_block(uint v) { return v / habuffer_light.block; }
