// Coherent probing of SPEC 3-5, written once for both paths.
// Host environment provides: uvec2 ha_table_size (H),
// uint ha_div_block(uint v) (v / B for the max-age block B), uint ha_max_age_cells_x, uvec2 ha_offset(uint i) (O[i],
// already cyclic for tables smaller than AMAX), and the slot index type
// ha_index (uint64_t on the CPU path).

// h_a(p) = (p + O[a-1]) mod H. Both terms are below H, so one conditional
// subtraction replaces the modulo.
uvec2 ha_probe(uvec2 p, uint age) {
  uvec2 h = p + ha_offset(age - 1u);
  if (h.x >= ha_table_size.x) h.x -= ha_table_size.x;
  if (h.y >= ha_table_size.y) h.y -= ha_table_size.y;
  return h;
}

// Age equivalence (SPEC 4): the unique pixel whose age-`age` probe is h.
uvec2 ha_owner(uvec2 h, uint age) {
  uvec2 o = ha_offset(age - 1u);
  uvec2 p = h + ha_table_size - o;
  if (p.x >= ha_table_size.x) p.x -= ha_table_size.x;
  if (p.y >= ha_table_size.y) p.y -= ha_table_size.y;
  return p;
}

// Row-major slot index, in the host's index type so tables above 2^32 work.
ha_index ha_slot(uvec2 h) { return ha_index(h.x) + ha_index(h.y) * ha_index(ha_table_size.x); }

// Max-age cell of pixel p (SPEC 5), row-major.
uint ha_cell(uvec2 p) { return ha_div_block(p.x) + ha_div_block(p.y) * ha_max_age_cells_x; }
