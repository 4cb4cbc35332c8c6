// Plain blending, the floor of time of every OIT comparison (and the ceiling
// of its error): the transparent fragments in front of the opaque surfaces
// over-blended by the fixed-function blender in submission order, unsorted,
// with no lists at all.
layout(location = 0) out vec4 r_out_colour;
layout(binding = 0) uniform sampler2D r_opaque_depth;  // t of the nearest opaque surface; 2 where none

void main() {
  if (r_depth() >= texelFetch(r_opaque_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
  r_out_colour = vec4(r_shaded_colour(), r_opacity);
}
