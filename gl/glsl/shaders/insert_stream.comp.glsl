// Compute entry: inserts a fragment stream held in a buffer through the same
// habuffer_insert a host fragment shader calls, one fragment per invocation (a 2D
// grid of work groups, so no invocation loops over several fragments and
// shares its loop budget on drivers that limit it, such as llvmpipe).
layout(local_size_x = 64) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer HaStream { HaFragment ha_stream[]; };
// Its count: a uniform on OpenGL, a push constant on Vulkan (whose GLSL
// defines VULKAN, GL_KHR_vulkan_glsl), the one entry of both paths.
#ifdef VULKAN
layout(push_constant) uniform HaStreamCount { uint ha_stream_count; };
#else
uniform uint ha_stream_count;
#endif

void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= ha_stream_count) return;
  HaFragment f = ha_stream[i];
  habuffer_insert(uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
}
