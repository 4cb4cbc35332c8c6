// Insertion of SPEC 6 (coherent Robin Hood hashing with atomicMax), written
// once for both paths, as a step function over the record being carried, so
// a host may run the steps in a loop (ha_insert_fragment) or hand a pending record to
// whichever thread owns its next slot (the CPU path's owner-computes mode).
//
// Host environment provides, besides ha_record.glsl, ha_carry.glsl,
// ha_saturation.glsl and ha_probe.glsl:
// ha_word ha_atomic_max_slot(ha_index s, ha_word r) (returns the old value),
// uint ha_atomic_missed() (0 when the last slot atomic happened; an emulated
// atomic that found its slot busy changed nothing and says HABUFFER_PENDING, probe
// again, or HABUFFER_CUT once it has been busy too long; always 0 where atomics are
// native),
// void ha_atomic_max_age(uint cell, uint age), uint habuffer_iter_limit, float
// habuffer_cull_tau (0 = early cull off), ha_word ha_load_slot(ha_index s) (a
// plain read), and HABUFFER_INOUT(T) (GLSL: inout T; C++: T&). A host may
// define HABUFFER_SLOT_READ_FIRST 0 to give every probe its atomic without
// the plain load first (the GL path's ModuleVariant::slot_read_first; the
// table is the same either way).

#ifndef HABUFFER_SLOT_READ_FIRST
#define HABUFFER_SLOT_READ_FIRST 1
#endif

// HABUFFER_PENDING while the carried record may probe again, else the failure
// that ends the call (SPEC 6 checks the age, then the iteration budget).
uint ha_insert_limit(HabufferCarry c) {
  if (c.a > ha_max_age()) return HABUFFER_FAILED_AGE;
  if (c.iter >= habuffer_iter_limit) return HABUFFER_FAILED_ITER;
  return HABUFFER_PENDING;
}

// One probe at h = ha_probe(c.p, c.a), within the limits. Returns HABUFFER_PENDING
// while a record (the same or an evicted one) must go on (the same probe
// again, carry unchanged, when an emulated atomic found its slot busy),
// HABUFFER_CUT when that atomic gave up (carry unchanged: the probe is made when the
// call resumes), else the HA_* outcome of the whole call.
// Whether the slot is known to hold a larger record than the carried one
// without an atomic: slots only grow during a gather, so a high word read
// above the carried record's belongs to a smaller value than the slot's
// current one, which already exceeds the record; atomicMax would change
// nothing. Early cull needs the opacity of a front record of the same pixel,
// which only a slot record of the carried age can be (age equivalence): that
// case still takes the atomic.
bool ha_slot_known_larger(ha_index s, HabufferCarry c, bool cull) {
  uint high = ha_high(ha_load_slot(s));
  if (high <= ha_high(c.r)) return false;
  return !cull || (high >> (32u - habuffer_age_bits)) > c.a;
}

// Whether the front record `old` (the carried pixel's, age c.a) may add its
// opacity to the carried one's. A call alone meets its pixel's records in
// decreasing order. Under concurrency, one not below the last counted is
// either that record moved ahead of this call by a concurrent call of the
// pixel (counting it again broke SPEC 6's bound: 0.016 against 0.0101 on an
// H100, and dropped fragments with 0.83 < tau = 0.9 in front on two CPU
// threads), or a nearer record placed after this call passed its slot.
// Records counted thus strictly decrease, so none counts twice; one left out
// only culls less. While acc is 0, every record counted had opacity 0, and
// counting it again adds nothing.
bool ha_front_is_new(HabufferCarry c, ha_word old) {
  return c.acc == 0.0f || old < ha_with_age(c.front, c.a);
}

// `cull`: habuffer_cull_tau > 0, an argument so that a run without early cull is
// compiled without it (ha_insert_run): carrying the cull's record cost the
// CPU path about 10 % of its inserts with the cull off.
uint ha_insert_step_at(HABUFFER_INOUT(HabufferCarry) c, uvec2 h, bool cull) {
  ha_index s = ha_slot(h);
  // A slot that loses to a record in place costs one plain load, not an
  // atomic (and, in emulated64, not a lock): at high depth complexity most
  // probes meet older, larger records.
  if (HABUFFER_SLOT_READ_FIRST != 0 && ha_slot_known_larger(s, c, cull)) {
    c.iter += 1u;
    c.a += 1u;
    c.r = ha_with_age(c.r, c.a);
    return HABUFFER_PENDING;
  }
  ha_word old = ha_atomic_max_slot(s, c.r);
  uint missed = ha_atomic_missed();
  if (missed != 0u) return missed;
  c.iter += 1u;
  if (old == c.r) return HABUFFER_DUPLICATE;
  if (old < c.r) {
    ha_atomic_max_age(ha_cell(c.p), c.a);
    if (old == ha_word(0)) return HABUFFER_STORED;
    // Carry the evicted record on: its pixel follows from its age alone.
    uint old_age = ha_age(old);
    c.r = old;
    c.p = ha_owner(h, old_age);
    // An evicted record behind its pixel's saturation depth is hidden as
    // surely as a new fragment there: it goes no further.
    if (ha_saturated(c.p, ha_code(c.r))) return HABUFFER_SATURATED;
    // Same pixel under early cull: retry the evicted record at this slot so
    // it first accumulates the opacity of the record that evicted it.
    if (cull && old_age == c.a) return HABUFFER_PENDING;
    c.acc = 0.0f;
    c.a = old_age;
  } else if (cull && ha_age(old) == c.a && ha_front_is_new(c, old)) {
    // A record of the same pixel lies in front: it hides the carried one.
    HABUFFER_PRECISE float acc = c.acc + (1.0f - c.acc) * ha_alpha(old);  // culls as the CPU path does
    c.acc = acc;
    c.front = old;
    if (c.acc > habuffer_cull_tau) {
      ha_saturate(c.p, ha_code(c.r));
      return HABUFFER_CULLED;
    }
  }
  c.a += 1u;
  c.r = ha_with_age(c.r, c.a);
  return HABUFFER_PENDING;
}

uint ha_insert_step(HABUFFER_INOUT(HabufferCarry) c, bool cull) {
  uint limit = ha_insert_limit(c);
  if (limit != HABUFFER_PENDING) return limit;
  return ha_insert_step_at(c, ha_probe(c.p, c.a), cull);
}

// Runs a call's steps until it ends. HABUFFER_CUT: cut short by something other
// than the table, with `c` holding the state to resume from: an emulated
// atomic gave up on a contended lock, or the driver ended the loop (Mesa
// llvmpipe gives a shader invocation about 65535 loop iterations in all, every
// loop together). Neither happens on the CPU path.
uint ha_insert_run(HABUFFER_INOUT(HabufferCarry) c) {
  uint outcome = HABUFFER_PENDING;
  if (habuffer_cull_tau > 0.0f) {
    while (outcome == HABUFFER_PENDING) outcome = ha_insert_step(c, true);
  } else {
    while (outcome == HABUFFER_PENDING) outcome = ha_insert_step(c, false);
  }
  return outcome == HABUFFER_PENDING ? HABUFFER_CUT : outcome;
}

uint ha_insert_code(uvec2 p, uint code, uint data) {
  if (ha_saturated(p, code)) return HABUFFER_SATURATED;
  HabufferCarry c = habuffer_carry_begin(p, code, data);
  return ha_insert_run(c);
}

// The whole insert call of one fragment on the CPU path (the GL entry
// habuffer_insert adds counting, capture and the deferral of calls cut short).
uint ha_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  return ha_insert_code(p, ha_fragment_code(t, coverage), data);
}
