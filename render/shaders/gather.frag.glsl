// Gather pass: every transparent fragment in front of the opaque surfaces
// goes through habuffer_insert; those behind are rejected first and counted. The
// same program is the counting pass (r_count_only 1: fragments per pixel,
// nothing inserted; sizing the table, depth complexity), so it compiles
// once, and on llvmpipe, which compiles a program at its first draw, the
// counting pass also readies the gather. Per-pixel counts in the inserting
// gather, each compiled in only where asked (an atomic add per fragment that
// no frame pays for unless it reads the counts: SceneRenderer::GatherCounts):
//   R_COUNT_FRAGMENTS  fragments per pixel, as the counting pass counts them;
//   R_COUNT_CULLED     fragments early cull rejected, per pixel.
// Fragments that insert nothing discard, so a technique that blends its
// inserts (wboit, blend) gets no output from them.
layout(std430, binding = R_BINDING_PIXEL_FRAGMENTS) buffer RPixelFragments { uint r_pixel_fragments[]; };
#ifdef R_COUNT_CULLED
layout(std430, binding = R_BINDING_PIXEL_CULLED) buffer RPixelCulled { uint r_pixel_culled[]; };
#endif
layout(std430, binding = R_BINDING_REJECTED) buffer RRejected { uint r_rejected; };
#ifdef R_SAMPLES
// A multisampled screen (R_SAMPLES per pixel): t of each sample's nearest
// opaque surface. The fragment keeps the samples it covers in front of
// theirs (its t is its pixel centre's, as the record stores it).
layout(binding = 0) uniform sampler2DMS r_opaque_depth;
#else
layout(binding = 0) uniform sampler2D r_opaque_depth;  // t of the nearest opaque surface; 2 where none
#endif
uniform uint r_screen_width;  // its own: the counting pass reads nothing of the technique's
uniform uint r_count_only;

void main() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  uint rgba = r_pack_rgba(r_shaded_colour(), r_opacity);  // derivatives before any branch
  float t = r_depth();
#ifdef R_SAMPLES
  uint coverage = uint(gl_SampleMaskIn[0]);
  for (int s = 0; s < R_SAMPLES; ++s)
    if (t >= texelFetch(r_opaque_depth, ivec2(p), s).r) coverage &= ~(1u << uint(s));
  if (coverage == 0u) {
#else
  if (t >= texelFetch(r_opaque_depth, ivec2(p), 0).r) {
#endif
    atomicAdd(r_rejected, 1u);
    discard;
  }
  uint i = p.x + p.y * r_screen_width;
  if (r_count_only != 0u) {
    atomicAdd(r_pixel_fragments[i], 1u);
    discard;
  }
#ifdef R_COUNT_FRAGMENTS
  atomicAdd(r_pixel_fragments[i], 1u);
#endif
#ifdef R_SAMPLES
  uint outcome = habuffer_insert(p, t, coverage, rgba);
#else
  uint outcome = habuffer_insert(p, t, rgba);
#endif
#ifdef R_COUNT_CULLED
  if (outcome == HABUFFER_CULLED) atomicAdd(r_pixel_culled[i], 1u);
#endif
}
