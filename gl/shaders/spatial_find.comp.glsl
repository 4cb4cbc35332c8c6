// The spatial hash's batched lookup on the GPU: one folded key per
// invocation (keys outside the domain were refused by the host), its slot's
// value and whether it was found.
layout(local_size_x = 64) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer ShQueries { uvec2 sh_queries[]; };
layout(std430, binding = HABUFFER_BINDING_CAPTURE) writeonly buffer ShAnswers { uvec2 sh_answers[]; };  // (found, stored value)

uniform uint sh_count;

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= sh_count) return;
  uint probes = 0u;
  ha_index s = sh_find_slot(sh_queries[i], probes);
  uvec2 answer = uvec2(0u, 0u);
  if (s != ~ha_index(0)) {
    sh_word r = sh_load_slot(s);
    if (sh_live(r) != 0u) answer = uvec2(1u, sh_value(r));
  }
  sh_answers[i] = answer;
}
