// The insertion entry of every technique on the GPU, for host fragment
// shaders and our compute entry: HABUFFER_TECHNIQUE_CALL (the module assembly
// names the technique's insert call) plus the outcome tallies (SPEC
// invariant 1 on the GPU) and the capture of entry_common.glsl. A pixel
// outside the screen cannot be inserted: it counts as invalid and is not
// captured (a replay could not insert it either). Returns the outcome, or
// HABUFFER_PENDING for a call deferred to the resume pass (counted there), or
// HABUFFER_UNCOUNTED in a pass that inserts nothing (the k-buffer's fill pass).
uint habuffer_insert(uvec2 pixel, float depth, uint rgba) {
#ifdef HABUFFER_STAGE_FRAGMENT
  // Helper invocations' stores and atomics have no effect: skip the work.
  if (gl_HelperInvocation) return HABUFFER_INVALID;
#endif
#ifdef HABUFFER_TECHNIQUE_BEGIN
  HABUFFER_TECHNIQUE_BEGIN();  // the blended baselines: no contribution unless the call blends
#endif
  uint outcome = HABUFFER_INVALID;
  if (all(lessThan(pixel, habuffer_screen_size))) {
    if (habuffer_capture_capacity > 0u && habuffer_gather_phase == 0u) ha_capture(pixel, depth, rgba);
    if (habuffer_capture_only != 0u) return HABUFFER_INVALID;
    outcome = HABUFFER_TECHNIQUE_CALL(pixel, depth, rgba);
  } else {
    // Counted once per frame: not in a pass that inserts nothing (the k-buffer's fill pass).
    if (habuffer_gather_phase != 0u) return HABUFFER_UNCOUNTED;
    ha_counter_add(pixel, HABUFFER_COUNTER_OFF_SCREEN, 1u);
  }
  if (outcome < HABUFFER_OUTCOME_COUNT) ha_counter_add(pixel, outcome, 1u);
  return outcome;
}

// Depth-only form (L32 records carry no payload).
uint habuffer_insert(uvec2 pixel, float depth) { return habuffer_insert(pixel, depth, 0u); }

// A straight-alpha colour in the module's rgba packing (R<<24 | G<<16 |
// B<<8 | A, each round(clamp(c, 0, 1) * 255) as packUnorm4x8 rounds).
uint ha_pack_rgba(vec4 colour) { return packUnorm4x8(colour.abgr); }

#ifdef HABUFFER_STAGE_FRAGMENT
// The current fragment at its pixel and window depth, with a straight-alpha
// colour: gl_FragCoord.z (0 nearest), or 1 - gl_FragCoord.z for a host
// whose depth convention is reversed-Z (GlFrameOptions::depth: 1 nearest,
// GL_GREATER), so the lists are nearest first either way.
uint habuffer_insert_here(vec4 colour) {
  float depth = habuffer_depth_reversed != 0u ? 1.0 - gl_FragCoord.z : gl_FragCoord.z;
  return habuffer_insert(uvec2(gl_FragCoord.xy), depth, ha_pack_rgba(colour));
}
#endif

// The names hosts called before the library took one prefix (habuffer_) for
// what every technique shares: kept, so a host shader written for them
// compiles unchanged. New code calls habuffer_insert and habuffer_insert_here.
#define ha_insert habuffer_insert
#define ha_insert_here habuffer_insert_here
