// Compute entry: inserts a fragment stream held in a buffer and counts each
// insert call's outcome (SPEC invariant 1).
layout(local_size_x = 64) in;

struct HaFragment {
  uint x;
  uint y;
  float depth;
  uint rgba;
};
layout(std430, binding = 3) readonly buffer HaFragments { HaFragment ha_fragments[]; };
layout(std430, binding = 4) buffer HaCounters { uint ha_counters[8]; };
uniform uint ha_fragment_count;

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < ha_fragment_count; i += stride) {
    HaFragment f = ha_fragments[i];
    atomicAdd(ha_counters[ha_insert(uvec2(f.x, f.y), f.depth, f.rgba)], 1u);
  }
}
