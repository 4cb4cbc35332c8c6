// The state of one insert call between steps, written once for both paths:
// the HA-buffer's probes (ha_insert.glsl) and the k-buffer's layers
// (kbuffer.glsl) carry the same fields, so the GPU path defers and
// resumes either through the same buffer (gl/glsl/shaders/ha_entry.glsl).
// Needs ha_record.glsl.

struct HabufferCarry {
  uvec2 p;      // pixel of the carried record (age equivalence gives it back after an eviction)
  uint a;       // HA-buffer: age about to be tried (may reach AMAX + 1); k-buffer: layer + 1
  ha_word r;    // the carried record, with age a while a <= AMAX (k-buffer: age 1 always)
  float acc;    // early cull: opacity accumulated in front of the carried record
  uint iter;    // probes made so far by this call
  ha_word front;  // early cull: the last record counted into acc (its age is ignored; see ha_front_is_new)
};

HabufferCarry habuffer_carry_begin(uvec2 p, uint code, uint data) {
  HabufferCarry c;
  c.p = p;
  c.a = 1u;
  c.r = ha_pack(1u, code, data);
  c.acc = 0.0f;
  c.iter = 0u;
  c.front = ha_word(0);
  return c;
}
