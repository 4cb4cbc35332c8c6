// The HA-buffer's insertion entry on the GPU, for host fragment shaders and
// our compute entry: the shared insert (ha_insert_run) plus the outcome
// tallies and capture of entry_common.glsl, and the deferral of calls cut
// short: their carried state goes to a buffer that the frame's resume pass
// (resume.comp.glsl) runs on until every call has ended, so contention and
// the driver's loop budget lose nothing.

// A HaCarry in a buffer (std430, 32 bytes): the record split in 32-bit halves.
struct HaDeferred {
  uvec2 p;
  uint a;
  float acc;
  uint iter;
  uint pad;
  uvec2 r;  // (low, high) words; high is 0 for L32
};

layout(std430, binding = HA_BINDING_DEFERRED) buffer HaDeferredCalls {
  uint ha_deferred_count;  // may exceed the capacity: the host sees the overflow and gathers again
  uint ha_deferred_pad0;
  uint ha_deferred_pad1;
  uint ha_deferred_pad2;
  HaDeferred ha_deferred[];
};

void ha_defer(HaCarry c) {
  uint i = atomicAdd(ha_deferred_count, 1u);
  if (i < ha_deferred_capacity) ha_deferred[i] = HaDeferred(c.p, c.a, c.acc, c.iter, 0u, ha_word_split(c.r));
}

HaCarry ha_carry_from(HaDeferred d) {
  HaCarry c;
  c.p = d.p;
  c.a = d.a;
  c.r = ha_word_join(d.r);
  c.acc = d.acc;
  c.iter = d.iter;
  return c;
}

// Ends a call (or one resumption of it): a call cut short is deferred and
// returns HA_PENDING (its outcome is counted when the resume pass ends it);
// any other outcome is tallied once, in the stripe of `pixel`.
uint ha_end_call(uvec2 pixel, HaCarry c, uint outcome) {
  uint base = ha_counter_stripe(pixel) * HA_COUNTER_STRIDE;
  if (ha_count_writes != 0u && ha_call_writes != 0u)
    atomicAdd(ha_counters[base + HA_COUNTER_SLOT_WRITES], ha_call_writes);
  if (outcome == HA_CUT) {
    ha_defer(c);
    return HA_PENDING;
  }
  atomicAdd(ha_counters[base + outcome], 1u);
  return outcome;
}

// Inserts one fragment and counts its outcome. A pixel outside the screen
// cannot be inserted (its max-age cell does not exist): it counts as invalid
// and is not captured (a replay could not insert it either). Returns the
// outcome, or HA_PENDING for a call cut short and deferred to the resume pass.
uint ha_insert(uvec2 pixel, float depth, uint rgba) {
#ifdef HA_STAGE_FRAGMENT
  // Helper invocations' stores and atomics have no effect: skip the work.
  if (gl_HelperInvocation) return HA_INVALID;
#endif
  HaCarry c;
  uint outcome = HA_INVALID;
  ha_call_writes = 0u;
  if (all(lessThan(pixel, ha_screen_size))) {
    if (ha_capture_capacity > 0u) ha_capture(pixel, depth, rgba);
    if (ha_capture_only != 0u) return HA_INVALID;
    if (ha_depth_valid(depth)) {
      c = ha_carry_begin(pixel, ha_depth_code(depth), rgba);
      outcome = ha_insert_run(c);
    }
  }
  return ha_end_call(pixel, c, outcome);
}

// Depth-only form (L32 records carry no payload).
uint ha_insert(uvec2 pixel, float depth) { return ha_insert(pixel, depth, 0u); }
