// The resolve pass into a host's image (SPEC 7), the Vulkan frame driver's:
// one invocation per pixel composites its list front to back over what the
// image holds there (the host's opaque pass), in place, as the OpenGL
// path's resolve_over does by blending: colour C + T * destination, alpha
// (1 - T) + T * destination alpha, so a pixel with nothing stored keeps its
// colour exactly. Texel (x, y) is pixel (x, y), the pixel the host's gather
// passed to habuffer_insert (Vulkan's framebuffer origin, top left).
// HABUFFER_TARGET_FORMAT is the image's format qualifier (rgba8, rgba16f,
// rgba32f).
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0, HABUFFER_TARGET_FORMAT) uniform image2D habuffer_target;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, habuffer_screen_size))) return;
  vec4 destination = imageLoad(habuffer_target, ivec2(p));
  vec4 composited = HABUFFER_TECHNIQUE_COMPOSITE(p, destination.rgb);
  float alpha = composited.a + (1.0 - composited.a) * destination.a;
  imageStore(habuffer_target, ivec2(p), vec4(composited.rgb, alpha));
}
