// The spatial hash's insert on the GPU: one record per invocation (a 2D
// grid of work groups), from the records buffer (folded key, stored value)
// or, when sh_resume is 1, from the carries of calls cut short by the last
// pass. Each call ends in one outcome, tallied; a failed call's carried
// record goes to the dropped buffer (the host grows the table and inserts
// again, as the CPU path does); a cut call's carry to the next pass's input.
layout(local_size_x = 64) in;

// The input, as words: on the first pass record i is words 4i .. 4i+3
// (x, y, value, 0); on a resume pass carry i is words 8i .. 8i+7, as
// ShCarryOut. Points: GlBindings' stream, deferred, capture and counters.
struct ShCarryOut { uint px, py, a, iter, low, high, pad0, pad1; };

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer ShInput { uint sh_input[]; };
layout(std430, binding = HABUFFER_BINDING_DEFERRED) buffer ShResumeOut { ShCarryOut sh_resume_out[]; };
layout(std430, binding = HABUFFER_BINDING_CAPTURE) buffer ShDropped { uvec4 sh_dropped[]; };
// counters[0 .. HABUFFER_SH_OUTCOME_COUNT-1]: outcomes; [8]: cut calls written; [9]: dropped written.
layout(std430, binding = HABUFFER_BINDING_COUNTERS) buffer ShCounters { uint sh_counters[]; };

uniform uint sh_count;
uniform uint sh_resume;

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= sh_count) return;
  ShCarry c;
  if (sh_resume == 0u) {
    c = sh_carry_begin(uvec2(sh_input[4u * i], sh_input[4u * i + 1u]), 1u, sh_input[4u * i + 2u]);
  } else {
    uint w = 8u * i;
    c.p = uvec2(sh_input[w], sh_input[w + 1u]);
    c.a = sh_input[w + 2u];
    c.iter = sh_input[w + 3u];
    c.r = sh_word_of(sh_input[w + 5u], sh_input[w + 4u]);
  }
  uint outcome = sh_insert_run(c);
  if (outcome == HABUFFER_SH_CUT) {
    uint at = atomicAdd(sh_counters[8], 1u);
    sh_resume_out[at] = ShCarryOut(c.p.x, c.p.y, c.a, c.iter, sh_low(c.r), sh_high(c.r), 0u, 0u);
    return;
  }
  atomicAdd(sh_counters[outcome], 1u);
  if (outcome == HABUFFER_SH_FAILED_AGE || outcome == HABUFFER_SH_FAILED_ITER) {
    uint at = atomicAdd(sh_counters[9], 1u);
    sh_dropped[at] = uvec4(sh_carry_key(c), sh_value(c.r), 0u);
  }
}
