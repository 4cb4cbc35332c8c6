// Traversal and compositing of SPEC 7, written once for both paths. Host
// environment provides ha_word ha_load_slot(ha_index s) and
// uint ha_load_max_age(uint cell).

// One step of the front-to-back walk of pixel p: the record at age `age`
// belongs to p (emit), belongs to another pixel (skip), or proves by the
// paper's Proposition A that p has no record at this age or beyond (stop).
uint ha_visit(ha_word r, uint age) {
  uint ra = ha_age(r);
  if (ra == age) return HA_VISIT_EMIT;
  return ra < age ? HA_VISIT_STOP : HA_VISIT_SKIP;
}

vec4 ha_unpack_rgba(uint data) {
  return vec4(float(data >> 24u), float((data >> 16u) & 255u), float((data >> 8u) & 255u),
              float(data & 255u)) * (1.0f / 255.0f);
}

// Straight-alpha front-to-back "under" operator, float32.
vec4 ha_blend_under(vec4 c, vec4 f) {
  float w = (1.0f - c.a) * f.a;
  return vec4(vec3(c) + w * vec3(f), c.a + w);
}

vec4 ha_finish(vec4 c, vec3 background) {
  return vec4(vec3(c) + (1.0f - c.a) * background, c.a);
}

// Composite every record of pixel p over the background.
vec4 ha_composite(uvec2 p, vec3 background) {
  vec4 c = vec4(0.0f);
  uint amax = ha_load_max_age(ha_cell(p));
  for (uint a = 1u; a <= amax; ++a) {
    ha_word r = ha_load_slot(ha_slot(ha_probe(p, a)));
    uint v = ha_visit(r, a);
    if (v == HA_VISIT_STOP) break;
    if (v == HA_VISIT_EMIT) c = ha_blend_under(c, ha_unpack_rgba(ha_data(r)));
  }
  return ha_finish(c, background);
}
