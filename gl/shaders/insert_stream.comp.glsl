// Compute entry: inserts a fragment stream held in a buffer through the same
// ha_insert a host fragment shader calls.
layout(local_size_x = 64) in;

layout(std430, binding = HA_BINDING_STREAM) readonly buffer HaStream { HaFragment ha_stream[]; };
uniform uint ha_stream_count;

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < ha_stream_count; i += stride) {
    HaFragment f = ha_stream[i];
    ha_insert(uvec2(f.x, f.y), f.depth, f.rgba);
  }
}
