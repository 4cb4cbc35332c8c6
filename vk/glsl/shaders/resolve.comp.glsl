// The resolve pass on Vulkan (SPEC 7): one invocation per pixel composites
// its list front to back over the pixel's background, as the OpenGL path's
// resolve.frag.glsl does into its framebuffer. The image is one buffer of
// RGBA floats, row 0 at the bottom, at the stream's binding point (the
// gather is over): its rgb the background on entry, the composited colour
// on return.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = HABUFFER_BINDING_STREAM) buffer HaImage { vec4 ha_image[]; };

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, habuffer_screen_size))) return;
  uint i = p.y * habuffer_screen_size.x + p.x;
  ha_image[i] = HABUFFER_TECHNIQUE_COMPOSITE(p, ha_image[i].rgb);
}
