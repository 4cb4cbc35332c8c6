// habuffer-view's gather: the host's own shader around the module's
// habuffer_insert (appended after the module and shading.glsl). Each
// transparent fragment in front of the opaque surfaces is inserted. Counted
// only where compiled in (an atomic per fragment nobody reads costs):
//   V_COUNT_PIXELS  the fragments and the early-culled ones per pixel, for
//                   the heat maps (v_counts: two words a pixel);
//   V_COUNT_CALLS   the calls in all (v_calls), the frame driver's call
//                   count where the driver can end a call unanswered.
layout(std430, binding = V_BINDING_COUNTS) buffer VCounts { uint v_calls; uint v_counts[]; };
#ifdef V_SAMPLES
layout(binding = 0) uniform sampler2DMS v_opaque_t;  // t of each sample's nearest opaque surface
#else
layout(binding = 0) uniform sampler2D v_opaque_t;  // t of the nearest opaque surface; 2 where none
#endif
uniform uint v_screen_width;

void main() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  uint rgba = r_pack_rgba(r_shaded_colour(), r_opacity);  // derivatives before any branch
  float t = r_depth();
#ifdef V_SAMPLES
  uint coverage = uint(gl_SampleMaskIn[0]);
  for (int s = 0; s < V_SAMPLES; ++s)
    if (t >= texelFetch(v_opaque_t, ivec2(p), s).r) coverage &= ~(1u << uint(s));
  if (coverage == 0u) discard;
  uint outcome = habuffer_insert(p, t, coverage, rgba);
#else
  if (t >= texelFetch(v_opaque_t, ivec2(p), 0).r) discard;
  uint outcome = habuffer_insert(p, t, rgba);
#endif
#ifdef V_COUNT_CALLS
  atomicAdd(v_calls, 1u);
#endif
#ifdef V_COUNT_PIXELS
  uint i = 2u * (p.x + p.y * v_screen_width);
  atomicAdd(v_counts[i], 1u);
  if (outcome == HABUFFER_CULLED) atomicAdd(v_counts[i + 1u], 1u);
#endif
}
