// Insertion of SPEC 6 (coherent Robin Hood hashing with atomicMax), written
// once for both paths, as a step function over the record being carried, so
// a host may run the steps in a loop (ha_insert_fragment) or hand a pending record to
// whichever thread owns its next slot (the CPU path's owner-computes mode).
//
// Host environment provides, besides ha_record.glsl and ha_probe.glsl:
// ha_word ha_atomic_max_slot(ha_index s, ha_word r) (returns the old value),
// bool ha_atomic_gave_up() (an emulated atomic hit its spin bound: the call
// fails as failed_iter; always false where atomics are native),
// void ha_atomic_max_age(uint cell, uint age), uint ha_iter_limit, float
// ha_cull_tau (0 = early cull off), void ha_loop_cut() (notes a call the
// driver's loop budget ended; nothing on the CPU), and HA_INOUT(T) (GLSL:
// inout T; C++: T&).

// The state of one insert call between probes.
struct HaCarry {
  uvec2 p;      // pixel of the carried record (age equivalence gives it back after an eviction)
  uint a;       // age about to be tried; may reach AMAX + 1, which no record can hold
  ha_word r;    // the carried record, with age a while a <= AMAX
  float acc;    // early cull: opacity accumulated in front of the carried record
  uint iter;    // probes made so far by this call
};

HaCarry ha_carry_begin(uvec2 p, uint code, uint data) {
  HaCarry c;
  c.p = p;
  c.a = 1u;
  c.r = ha_pack(1u, code, data);
  c.acc = 0.0f;
  c.iter = 0u;
  return c;
}

// HA_PENDING while the carried record may probe again, else the failure
// that ends the call (SPEC 6 checks the age, then the iteration budget).
uint ha_insert_limit(HaCarry c) {
  if (c.a > ha_max_age()) return HA_FAILED_AGE;
  if (c.iter >= ha_iter_limit) return HA_FAILED_ITER;
  return HA_PENDING;
}

// One probe at h = ha_probe(c.p, c.a), within the limits. Returns HA_PENDING
// while a record (the same or an evicted one) must go on, else the HA_*
// outcome of the whole call.
uint ha_insert_step_at(HA_INOUT(HaCarry) c, uvec2 h) {
  c.iter += 1u;
  ha_word old = ha_atomic_max_slot(ha_slot(h), c.r);
  if (ha_atomic_gave_up()) return HA_FAILED_ITER;
  if (old == c.r) return HA_DUPLICATE;
  bool cull = ha_cull_tau > 0.0f;
  if (old < c.r) {
    ha_atomic_max_age(ha_cell(c.p), c.a);
    if (old == ha_word(0)) return HA_STORED;
    // Carry the evicted record on: its pixel follows from its age alone.
    uint old_age = ha_age(old);
    c.r = old;
    c.p = ha_owner(h, old_age);
    // Same pixel under early cull: retry the evicted record at this slot so
    // it first accumulates the opacity of the record that evicted it.
    if (cull && old_age == c.a) return HA_PENDING;
    c.acc = 0.0f;
    c.a = old_age;
  } else if (cull && ha_age(old) == c.a) {
    // A record of the same pixel lies in front: it hides the carried one.
    c.acc += (1.0f - c.acc) * ha_alpha(old);
    if (c.acc > ha_cull_tau) return HA_CULLED;
  }
  c.a += 1u;
  c.r = ha_with_age(c.r, c.a);
  return HA_PENDING;
}

uint ha_insert_step(HA_INOUT(HaCarry) c) {
  uint limit = ha_insert_limit(c);
  if (limit != HA_PENDING) return limit;
  return ha_insert_step_at(c, ha_probe(c.p, c.a));
}

// The last line is defensive: a driver may end a long loop early (Mesa
// llvmpipe gives a shader invocation about 65535 loop iterations in all), and
// a call ended that way still fails as failed_iter instead of leaving an
// outcome uncounted.
uint ha_insert_code(uvec2 p, uint code, uint data) {
  HaCarry c = ha_carry_begin(p, code, data);
  uint outcome = HA_PENDING;
  while (outcome == HA_PENDING) outcome = ha_insert_step(c);
  if (outcome != HA_PENDING) return outcome;
  ha_loop_cut();
  return HA_FAILED_ITER;
}

// The whole insert call of one fragment (the GL entry ha_insert adds counting
// and capture around it).
uint ha_insert_fragment(uvec2 p, float t, uint data) {
  if (!ha_depth_valid(t)) return HA_INVALID;
  return ha_insert_code(p, ha_depth_code(t), data);
}
