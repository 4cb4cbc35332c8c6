// The spatial hash's parameters (GlSpatialHash writes them once per table),
// read by the library's compute passes (spatial_env.glsl) and by a host
// shader's lookup (spatial_lookup_env.glsl) alike: one std140 block at the
// uniform point HABUFFER_SPATIAL_BINDING_PARAMS.
layout(std140, binding = HABUFFER_SPATIAL_BINDING_PARAMS) uniform HabufferSpatial {
  uvec2 table_size;       // H
  uint age_bits;          // A
  uint quotient_x;        // qx = ceil(Du / Hx)
  uint max_age_cells_x;   // max-age cells per row
  uint block;             // the max-age block B
  uint iter_limit;        // probes of one insert call
  uint complement;        // 1: values stored as complements (rule min)
  uvec3 domain;           // the key space (Dx, Dy, Dz)
  uint interleave_shift;  // log2 of the slices interleaved along x (G)
  uint slices_per_row;    // groups of slices per row of the fold (F)
  uint filter_blocks_x;   // miss-filter blocks per row (0: no filter)
  uint filter_base;       // the filter's first word in the max-age buffer (after the cells)
  uint filter_shift_y;    // log2 of a filter block's height
} habuffer_spatial;
