// The resume pass: one deferred insert call per invocation, resumed from its
// carried state where it was cut short (a lock given up, the driver's loop
// budget spent), with the same probe count, age, record and opacity, so the
// call ends exactly as an uninterrupted one would. A call cut short again is
// deferred again, into the other buffer, for the next round.
layout(local_size_x = 64) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer HaResumeCalls {
  uint ha_resume_header[4];
  HaDeferred ha_resume[];
};
// The calls to resume: the driver's count (Readback::Immediate) or the
// buffer's capacity with the count read here from its header, so a round
// is dispatched without the driver reading the count back (Deferred). A
// uniform on OpenGL, a push constant on Vulkan, as insert_stream.comp.glsl's.
#ifdef VULKAN
layout(push_constant) uniform HaResumeCount { uint ha_resume_count; };
#else
uniform uint ha_resume_count;
#endif

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= min(ha_resume_count, ha_resume_header[0])) return;
  HabufferCarry c = ha_carry_from(ha_resume[i]);
  ha_call_writes = 0u;
  // Two statements: arguments are evaluated left to right, so one call would
  // pass the carry as it was before the run.
  uint outcome = HABUFFER_CARRY_RUN(c);
  outcome = ha_end_run(c.p, c, outcome);
  if (outcome != HABUFFER_PENDING) ha_counter_add(c.p, outcome, 1u);
}
