// The blended baselines' calls on the GPU (blended_env.glsl says how the
// blender does the accumulation): the insert writes the fragment's term, the
// composite finishes a pixel from the copied accumulators.
void bl_begin_call() {
#ifdef HABUFFER_BLENDED_OUTPUTS
  ha_blended_accum = vec4(0.0f);
#ifdef HABUFFER_WBOIT
  ha_blended_revealage = vec4(0.0f);
#endif
#endif
}

// The blended baselines store no lists: a multisampled host blends them per
// sample in its own target, so the coverage word is not read.
uint bl_insert_fragment(uvec2 pixel, float depth, uint coverage, uint rgba) {
  if (!ha_depth_valid(depth)) return HABUFFER_INVALID;
#ifdef HABUFFER_BLENDED_OUTPUTS
  if (any(notEqual(pixel, uvec2(gl_FragCoord.xy)))) return HABUFFER_INVALID;  // the blender writes here only
  vec4 f = ha_unpack_rgba(rgba);
#ifdef HABUFFER_WBOIT
  ha_blended_accum = wb_accum_term(depth, f);
  ha_blended_revealage = vec4(f.a);
#else
  ha_blended_accum = bl_term(f);
#endif
  return HABUFFER_BLENDED;
#else
  return HABUFFER_INVALID;  // no blender outside a fragment shader: habuffer_insert counts the call invalid
#endif
}

vec4 bl_composite(uvec2 p, vec3 background) {
  uint i = p.x + p.y * habuffer_screen_size.x;
#ifdef HABUFFER_WBOIT
  return wb_finish(ha_accum[i], ha_revealage[i], background);
#else
  return bl_finish(ha_accum[i], background);
#endif
}
