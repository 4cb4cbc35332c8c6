// The spatial hash's insert on the GPU: one record per invocation (a 2D
// grid of work groups), from the records buffer (folded key, stored value)
// or, when sh_resume is 1, from the carries of calls cut short by the last
// pass. Each call ends in one outcome, tallied; a failed call's carried
// record goes to the dropped buffer (the host grows the table and inserts
// again, as the CPU path does); a cut call's carry to the next pass's input.
layout(local_size_x = 64) in;

struct ShRecordIn { uint x, y, value, pad; };
struct ShCarryOut { uint px, py, a, iter, low, high, pad0, pad1; };

layout(std430, binding = 4) readonly buffer ShRecords { ShRecordIn sh_records[]; };
layout(std430, binding = 5) readonly buffer ShResumeIn { ShCarryOut sh_resume_in[]; };
layout(std430, binding = 6) buffer ShResumeOut { ShCarryOut sh_resume_out[]; };
layout(std430, binding = 7) buffer ShDropped { uvec4 sh_dropped[]; };
// counters[0 .. HABUFFER_SH_OUTCOME_COUNT-1]: outcomes; [8]: cut calls written; [9]: dropped written.
layout(std430, binding = 8) buffer ShCounters { uint sh_counters[]; };

uniform uint sh_count;
uniform uint sh_resume;

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= sh_count) return;
  ShCarry c;
  if (sh_resume == 0u) {
    ShRecordIn r = sh_records[i];
    c = sh_carry_begin(uvec2(r.x, r.y), 1u, r.value);
  } else {
    ShCarryOut o = sh_resume_in[i];
    c.p = uvec2(o.px, o.py);
    c.a = o.a;
    c.iter = o.iter;
    c.r = sh_word_of(o.high, o.low);
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
    uvec2 k = sh_key(c.p, sh_quotient(c.r));
    sh_dropped[at] = uvec4(k, sh_value(c.r), 0u);
  }
}
