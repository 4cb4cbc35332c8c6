// The floor of an A-buffer's gather: one atomic add per transparent
// fragment in front of the opaque surfaces (to its pixel's counter), and
// nothing else; a technique's gather is this plus its own work.
layout(std430, binding = R_BINDING_PIXEL_FRAGMENTS) buffer RPixelFragments { uint r_pixel_fragments[]; };
layout(binding = 0) uniform sampler2D r_opaque_depth;  // t of the nearest opaque surface; 2 where none
uniform uint r_screen_width;

void main() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  if (r_depth() >= texelFetch(r_opaque_depth, ivec2(p), 0).r) return;
  atomicAdd(r_pixel_fragments[p.x + p.y * r_screen_width], 1u);
}
