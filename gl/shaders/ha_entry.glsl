// The GPU path's public insertion functions, for host fragment shaders and
// our compute entry: the shared insert (ha_insert_fragment) plus the frame's
// outcome tallies (SPEC invariant 1 on the GPU) and the capture mode, which
// appends every incoming fragment so the CPU path can replay exactly what the
// rasterizer produced.
struct HaFragment {
  uint x;
  uint y;
  float depth;  // as given: the CPU path derives the same depth code from it
  uint rgba;
};

layout(std430, binding = HA_BINDING_COUNTERS) buffer HaCounters { uint ha_counters[]; };
layout(std430, binding = HA_BINDING_CAPTURE) buffer HaCapture {
  uint ha_capture_count;  // may exceed the capacity: the host sees the overflow and gathers again
  uint ha_capture_pad0;
  uint ha_capture_pad1;
  uint ha_capture_pad2;
  HaFragment ha_captured[];
};

void ha_capture(uvec2 pixel, float depth, uint rgba) {
  uint i = atomicAdd(ha_capture_count, 1u);
  if (i < ha_capture_capacity) ha_captured[i] = HaFragment(pixel.x, pixel.y, depth, rgba);
}

// Inserts one fragment and counts its outcome. A pixel outside the screen
// cannot be inserted (its max-age cell does not exist): it counts as invalid
// and is not captured (a replay could not insert it either).
uint ha_insert(uvec2 pixel, float depth, uint rgba) {
#ifdef HA_STAGE_FRAGMENT
  // Helper invocations' stores and atomics have no effect: skip the work.
  if (gl_HelperInvocation) return HA_INVALID;
#endif
  uint outcome = HA_INVALID;
  if (all(lessThan(pixel, ha_screen_size))) {
    if (ha_capture_capacity > 0u) ha_capture(pixel, depth, rgba);
    if (ha_capture_only != 0u) return HA_INVALID;
    ha_begin_call();
    ha_call_writes = 0u;
    outcome = ha_insert_fragment(pixel, depth, rgba);
    if (ha_call_cut_short()) atomicAdd(ha_counters[HA_COUNTER_CUT_SHORT * HA_COUNTER_STRIDE], 1u);
    if (ha_count_writes != 0u && ha_call_writes != 0u)
      atomicAdd(ha_counters[HA_COUNTER_SLOT_WRITES * HA_COUNTER_STRIDE], ha_call_writes);
  }
  atomicAdd(ha_counters[outcome * HA_COUNTER_STRIDE], 1u);
  return outcome;
}

// Depth-only form (L32 records carry no payload).
uint ha_insert(uvec2 pixel, float depth) { return ha_insert(pixel, depth, 0u); }
