// Insertion of SPEC 6 (coherent Robin Hood hashing with atomicMax), written
// once for both paths. Host environment provides, besides ha_record.glsl and
// ha_probe.glsl: ha_word ha_atomic_max_slot(ha_index s, ha_word r) (returns
// the old value), void ha_atomic_max_age(uint cell, uint age), uint
// ha_iter_limit, and float ha_cull_tau (0 = early cull off).
//
// Returns one HA_* outcome; the caller counts it (invariant 1).

uint ha_insert_code(uvec2 p, uint code, uint data) {
  bool cull = ha_cull_tau > 0.0f;
  uint a = 1u;
  ha_word r = ha_pack(a, code, data);
  float acc = 0.0f;  // opacity accumulated in front of the carried record
  for (uint iter = 0u;; ++iter) {
    if (a > ha_max_age()) return HA_FAILED_AGE;
    if (iter >= ha_iter_limit) return HA_FAILED_ITER;
    uvec2 h = ha_probe(p, a);
    ha_word old = ha_atomic_max_slot(ha_slot(h), r);
    if (old == r) return HA_DUPLICATE;
    if (old < r) {
      ha_atomic_max_age(ha_cell(p), a);
      if (old == ha_word(0)) return HA_STORED;
      // Carry the evicted record on: its pixel follows from its age alone.
      uint old_age = ha_age(old);
      r = old;
      p = ha_owner(h, old_age);
      // Same pixel under early cull: retry the evicted record at this slot so
      // it first accumulates the opacity of the record that evicted it.
      if (cull && old_age == a) continue;
      acc = 0.0f;
      a = old_age;
    } else if (cull && ha_age(old) == a) {
      // A record of the same pixel lies in front: it hides the carried one.
      acc += (1.0f - acc) * ha_alpha(old);
      if (acc > ha_cull_tau) return HA_CULLED;
    }
    a += 1u;
    r = ha_with_age(r, a);
  }
}

uint ha_insert(uvec2 p, float t, uint data) {
  if (!ha_depth_valid(t)) return HA_INVALID;
  return ha_insert_code(p, ha_depth_code(t), data);
}
