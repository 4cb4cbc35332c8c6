// The spatial hash's insert records on the GPU, from keys the way a host
// gives them (the library's upload of a span, or a host's own buffers): key
// i is (x, y, z, -) as uvec4 (std430 uvec3[] or uvec4[]: 16 bytes a key),
// its stored value word i of the values buffer (or 0 with
// sh_has_values 0). Each key in the domain becomes record i, (folded x,
// folded y, value, 0), for spatial_insert.comp.glsl's first pass; a key
// outside it is counted (counters[0]) and the smallest such index kept
// (counters[1]), and the host refuses the batch before any insert pass.
layout(local_size_x = 64) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer ShKeys { uvec4 sh_keys[]; };
layout(std430, binding = HABUFFER_BINDING_DEFERRED) readonly buffer ShValues { uint sh_values[]; };
layout(std430, binding = HABUFFER_BINDING_CAPTURE) writeonly buffer ShRecords { uvec4 sh_records[]; };
layout(std430, binding = HABUFFER_BINDING_COUNTERS) buffer ShKeyCounters { uint sh_key_counters[]; };

uniform uint sh_count;
uniform uint sh_has_values;

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= sh_count) return;
  uvec3 k = sh_keys[i].xyz;
  if (!sh_in_domain(k)) {
    atomicAdd(sh_key_counters[0], 1u);
    atomicMin(sh_key_counters[1], i);
    sh_records[i] = uvec4(0u);
    return;
  }
  sh_records[i] = uvec4(sh_fold(k), sh_has_values != 0u ? sh_values[i] : 0u, 0u);
}
