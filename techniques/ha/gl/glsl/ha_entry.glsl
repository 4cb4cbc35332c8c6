#ifndef HABUFFER_CARRY_RUN
#define HABUFFER_CARRY_RUN ha_insert_run
#endif
// The HA-buffer's part of the insertion entry on the GPU: the shared insert
// (ha_insert_run) as insert_entry.glsl's call, and the deferral of calls cut
// short: their carried state goes to a buffer that the frame's resume pass
// (resume.comp.glsl) runs on until every call has ended, so contention and
// the driver's loop budget lose nothing.

// A HabufferCarry in a buffer (std430, 40 bytes): the records split in 32-bit halves.
struct HaDeferred {
  uvec2 p;
  uint a;
  float acc;
  uint iter;
  uint pad;
  uvec2 r;      // (low, high) words; high is 0 for L32
  uvec2 front;  // the same split
};

layout(std430, binding = HABUFFER_BINDING_DEFERRED) buffer HaDeferredCalls {
  uint ha_deferred_count;  // may exceed the capacity: the host sees the overflow and gathers again
  uint ha_deferred_pad0;
  uint ha_deferred_pad1;
  uint ha_deferred_pad2;
  HaDeferred ha_deferred[];
};

void ha_defer(HabufferCarry c) {
  uint i = atomicAdd(ha_deferred_count, 1u);
  if (i < habuffer_deferred_capacity) ha_deferred[i] = HaDeferred(c.p, c.a, c.acc, c.iter, 0u, ha_word_split(c.r), ha_word_split(c.front));
}

HabufferCarry ha_carry_from(HaDeferred d) {
  HabufferCarry c;
  c.p = d.p;
  c.a = d.a;
  c.r = ha_word_join(d.r);
  c.acc = d.acc;
  c.iter = d.iter;
  c.front = ha_word_join(d.front);
  return c;
}

// Ends one run of a call (the call itself or a resumption): adds its slot
// writes (in the HABUFFER_COUNT_WRITES variant), and defers a call cut short,
// returning HABUFFER_PENDING (its outcome is counted when the resume pass ends
// it); any other outcome is returned for the caller to count.
uint ha_end_run(uvec2 pixel, HabufferCarry c, uint outcome) {
#ifdef HABUFFER_COUNT_WRITES
  if (ha_call_writes != 0u) ha_counter_add(pixel, HABUFFER_COUNTER_SLOT_WRITES, ha_call_writes);
#endif
  if (outcome == HABUFFER_CUT) {
    ha_defer(c);
    return HABUFFER_PENDING;
  }
  return outcome;
}

// One insert call of a valid depth code through HABUFFER_CARRY_RUN (the
// HA-buffer's ha_insert_run, or the k-buffer's kb_insert_run): its outcome,
// or HABUFFER_PENDING for a call cut short and deferred to the resume pass.
uint ha_call_code(uvec2 pixel, uint code, uint rgba) {
  ha_call_writes = 0u;
  HabufferCarry c = habuffer_carry_begin(pixel, code, rgba);
  uint outcome = HABUFFER_CARRY_RUN(c);
  return ha_end_run(pixel, c, outcome);
}

// The HA-buffer's insert call for insert_entry.glsl's habuffer_insert.
uint ha_call(uvec2 pixel, float depth, uint coverage, uint rgba) {
  if (!ha_fragment_valid(depth, coverage)) return HABUFFER_INVALID;
  uint code = ha_fragment_code(depth, coverage);
  if (ha_saturated(pixel, code)) return HABUFFER_SATURATED;
  return ha_call_code(pixel, code, rgba);
}
