// The spatial hash's batched lookup on the GPU: one key per invocation,
// looked up by spatial_keys.glsl's sh_find (the fold and probe a host
// shader's habuffer_spatial_find runs too): whether it was found and its
// stored value.
layout(local_size_x = 64) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer ShQueries { uvec4 sh_queries[]; };  // (x, y, z, -)
layout(std430, binding = HABUFFER_BINDING_CAPTURE) writeonly buffer ShAnswers { uvec2 sh_answers[]; };  // (found, stored value)

uniform uint sh_count;

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= sh_count) return;
  uint stored = 0u;
  bool found = sh_find(sh_queries[i].xyz, stored);
  sh_answers[i] = uvec2(found ? 1u : 0u, stored);
}
