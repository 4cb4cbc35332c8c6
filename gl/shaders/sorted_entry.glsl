// The insertion entry of the techniques that sort after the gather (linked
// lists, fixed arrays): HA_TECHNIQUE_INSERT (the module assembly names the
// technique's insert) plus the outcome tallies and capture of
// entry_common.glsl. Their calls never loop, so nothing is cut short.
uint ha_insert(uvec2 pixel, float depth, uint rgba) {
#ifdef HA_STAGE_FRAGMENT
  // Helper invocations' stores and atomics have no effect: skip the work.
  if (gl_HelperInvocation) return HA_INVALID;
#endif
  uint outcome = HA_INVALID;
  if (all(lessThan(pixel, ha_screen_size))) {
    if (ha_capture_capacity > 0u) ha_capture(pixel, depth, rgba);
    if (ha_capture_only != 0u) return HA_INVALID;
    outcome = HA_TECHNIQUE_INSERT(pixel, depth, rgba);
  }
  ha_count_outcome(pixel, outcome);
  return outcome;
}

// Depth-only form (L32 records carry no payload).
uint ha_insert(uvec2 pixel, float depth) { return ha_insert(pixel, depth, 0u); }
