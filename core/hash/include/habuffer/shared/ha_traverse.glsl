// Traversal and compositing of SPEC 7, written once for both paths. Host
// environment provides ha_word ha_load_slot(ha_index s) and
// uint ha_load_max_age(uint cell); compositing is ha_blend.glsl's.

// One step of the front-to-back walk of pixel p: the record at age `age`
// belongs to p (emit), belongs to another pixel (skip), or proves by the
// paper's Proposition A that p has no record at this age or beyond (stop).
uint ha_visit(ha_word r, uint age) {
  uint ra = ha_age(r);
  if (ra == age) return HABUFFER_VISIT_EMIT;
  return ra < age ? HABUFFER_VISIT_STOP : HABUFFER_VISIT_SKIP;
}

// Composite every record of pixel p over the background.
vec4 ha_composite(uvec2 p, vec3 background) {
  HABUFFER_PIXEL_COLOUR c = ha_pixel_begin();
  uint amax = ha_load_max_age(ha_cell(p));
  for (uint a = 1u; a <= amax; ++a) {
    ha_word r = ha_load_slot(ha_slot(ha_probe(p, a)));
    uint v = ha_visit(r, a);
    if (v == HABUFFER_VISIT_STOP) break;
    if (v == HABUFFER_VISIT_EMIT) ha_pixel_under(c, ha_code(r), ha_data(r));
  }
  return ha_pixel_finish(c, background);
}

// The light's transmittance at pixel p of a light-view buffer, for a
// receiver whose depth code from the light is `code` (seed 000's
// translucent shadow map, section 6): SPEC 7's walk, nearest first,
// multiplying (1 - alpha) of every record nearer than the receiver by more
// than `bias` codes (a record's code above code + bias; codes grow toward
// the light), stopping at the first record that is not. The bias keeps a
// surface's own records (at the receiver's code, or a few codes off where the
// surface is slanted to the light) from shadowing it. Alpha is the record's
// colour byte (L64); L32 records carry none and read as transparent.
// Needs ha_shadow.glsl (the step every path shares).
float ha_transmittance(uvec2 p, uint code, uint bias) {
  uint front = ha_shadow_front(code, bias, ha_max_code());
  float t = 1.0f;
  uint amax = ha_load_max_age(ha_cell(p));
  for (uint a = 1u; a <= amax; ++a) {
    ha_word r = ha_load_slot(ha_slot(ha_probe(p, a)));
    uint v = ha_visit(r, a);
    if (v == HABUFFER_VISIT_STOP) break;
    if (v == HABUFFER_VISIT_EMIT) {
      if (ha_code(r) <= front) break;
      t = ha_shadow_through(t, ha_data(r));
    }
  }
  return t;
}
