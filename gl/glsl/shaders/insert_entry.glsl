// The insertion entry of every technique on the GPU, for host fragment
// shaders and our compute entry: HABUFFER_TECHNIQUE_CALL (the module assembly
// names the technique's insert call) plus the outcome tallies (SPEC
// invariant 1 on the GPU) and the capture of entry_common.glsl. A pixel
// outside the screen cannot be inserted: it counts as invalid and is not
// captured (a replay could not insert it either). Returns the outcome, or
// HABUFFER_PENDING for a call deferred to the resume pass (counted there), or
// HABUFFER_UNCOUNTED in a pass that inserts nothing (the k-buffer's fill pass, the
// frame driver's counting gather).
//
// `coverage`: the samples of a multisampled screen the fragment covers, one
// bit per sample (gl_SampleMaskIn[0] in a fragment shader), 0 for the whole
// pixel; not read when the screen is not multisampled (docs/spec-notes.md,
// "Multisampled records").
uint habuffer_insert(uvec2 pixel, float depth, uint coverage, uint rgba) {
#ifdef HABUFFER_STAGE_FRAGMENT
  // Helper invocations' stores and atomics have no effect: skip the work.
  if (gl_HelperInvocation) return HABUFFER_INVALID;
#endif
#ifdef HABUFFER_MODULE_ID
  // A shader built from another driver's module_source() (another technique,
  // mode, binding points or variant): nothing inserted, the call counted for
  // the driver to refuse the frame (the installed files define no fingerprint).
  if (habuffer_module_id != HABUFFER_MODULE_ID) {
    atomicAdd(ha_counters[HABUFFER_COUNTER_FOREIGN], 1u);
    return HABUFFER_INVALID;
  }
#endif
  // The frame driver's counting gather: every on-screen call counted once,
  // nothing inserted or captured (it sizes an automatic container).
  if (habuffer_gather_phase == HABUFFER_PHASE_COUNT) {
    if (all(lessThan(pixel, habuffer_screen_size))) ha_counter_add(pixel, HABUFFER_COUNTER_COUNTED, 1u);
    return HABUFFER_UNCOUNTED;
  }
#ifdef HABUFFER_TECHNIQUE_BEGIN
  HABUFFER_TECHNIQUE_BEGIN();  // the blended baselines: no contribution unless the call blends
#endif
  uint outcome = HABUFFER_INVALID;
  if (all(lessThan(pixel, habuffer_screen_size))) {
    if (habuffer_capture_capacity > 0u && habuffer_gather_phase == 0u) ha_capture(pixel, depth, coverage, rgba);
    if (habuffer_capture_only != 0u) return HABUFFER_INVALID;
#ifdef HABUFFER_COUNT_CALLS
    // Counted before the call can be cut short (HABUFFER_COUNTER_CALLS).
    if (habuffer_gather_phase == HABUFFER_PHASE_INSERT) atomicAdd(ha_counters[HABUFFER_COUNTER_CALLS], 1u);
#endif
    // A lossless attempt that will be gathered again: after its first
    // failure the calls are only counted (HABUFFER_COUNTER_FAILED_ONCE). A
    // stale read of the flag inserts a call more, which is harmless.
    if (habuffer_stop_at_failure != 0u && ha_counters[HABUFFER_COUNTER_FAILED_ONCE] != 0u) {
      ha_counter_add(pixel, HABUFFER_COUNTER_COUNTED, 1u);
      return HABUFFER_UNCOUNTED;
    }
    outcome = HABUFFER_TECHNIQUE_CALL(pixel, depth, coverage, rgba);
    if (habuffer_stop_at_failure != 0u && (outcome == HABUFFER_FAILED_AGE || outcome == HABUFFER_FAILED_ITER))
      ha_counters[HABUFFER_COUNTER_FAILED_ONCE] = 1u;
  } else {
    // Counted once per frame: not in a pass that inserts nothing (the k-buffer's fill pass).
    if (habuffer_gather_phase != 0u) return HABUFFER_UNCOUNTED;
    ha_counter_add(pixel, HABUFFER_COUNTER_OFF_SCREEN, 1u);
  }
  if (outcome < HABUFFER_OUTCOME_COUNT) ha_counter_add(pixel, outcome, 1u);
  return outcome;
}

// The current invocation's coverage: in a fragment shader on a multisampled
// screen, the samples the rasterizer gave it (gl_SampleMaskIn[0]); else 0,
// the whole pixel.
uint habuffer_coverage_here() {
#ifdef HABUFFER_STAGE_FRAGMENT
  if (habuffer_coverage_bits != 0u) return uint(gl_SampleMaskIn[0]);
#endif
  return 0u;
}

// A fragment of the current invocation's coverage (habuffer_coverage_here).
// In a fragment shader the rasterizer's sample count must be the buffer's:
// a fragment of a multisampled framebuffer in a buffer of one sample would
// be resolved from one sample, a buffer of S samples needs S-bit masks, so
// such calls insert nothing and the driver refuses the frame.
uint habuffer_insert(uvec2 pixel, float depth, uint rgba) {
// Vulkan's GLSL has no gl_NumSamples (the pipeline holds the count): its
// frame driver runs screens of one sample and refuses the others.
#if defined(HABUFFER_STAGE_FRAGMENT) && !defined(VULKAN)
  uint samples = uint(max(gl_NumSamples, 1));
  if (samples != max(habuffer_coverage_bits, 1u)) {
    atomicAdd(ha_counters[HABUFFER_COUNTER_SAMPLES_MISMATCH], 1u);
    atomicMax(ha_counters[HABUFFER_COUNTER_SAMPLES_SEEN], samples);
    return HABUFFER_INVALID;
  }
#endif
  return habuffer_insert(pixel, depth, habuffer_coverage_here(), rgba);
}

// Depth-only form (L32 records carry no payload).
uint habuffer_insert(uvec2 pixel, float depth) { return habuffer_insert(pixel, depth, 0u); }

// A straight-alpha colour in the module's rgba packing (R<<24 | G<<16 |
// B<<8 | A, each round(clamp(c, 0, 1) * 255) as packUnorm4x8 rounds).
uint ha_pack_rgba(vec4 colour) { return packUnorm4x8(colour.abgr); }

#ifdef HABUFFER_STAGE_FRAGMENT
// A light pass's t of window depth z (GlFrameOptions::light): the light's
// projection and window mapping inverted, linear in its eye distance
// (GlLightDepthMap in habuffer/gl/light_mapping.h), clamped to [0, 1]: the
// rasterizer clips at the projection's planes, rounding may step past them.
float habuffer_light_depth(float z) {
  return clamp((habuffer_light_a * z + habuffer_light_b) / (habuffer_light_c * z + habuffer_light_d), 0.0, 1.0);
}

// The current fragment at its pixel and window depth, with a straight-alpha
// colour: gl_FragCoord.z (0 nearest), or 1 - gl_FragCoord.z for a host
// whose depth convention is reversed-Z (GlFrameOptions::depth: 1 nearest,
// GL_GREATER), so the lists are nearest first either way. In a light pass
// (GlFrameOptions::light) the light's t of it, as habuffer_insert_light.
uint habuffer_insert_here(vec4 colour) {
  float z = gl_FragCoord.z;
  float depth = habuffer_light_gather != 0u ? habuffer_light_depth(z) : habuffer_depth_reversed != 0u ? 1.0 - z : z;
  return habuffer_insert(uvec2(gl_FragCoord.xy), depth, ha_pack_rgba(colour));
}

#ifdef HABUFFER_LIGHT_GATHER
// A light pass's insert (GlFrameOptions::light, which makes the driver's
// module define HABUFFER_LIGHT_GATHER): the current fragment at the depth t
// the light lookup compares, from gl_FragCoord.z through the light's
// projection. Without the light in the block (a module compiled with the
// define by hand) nothing is stored: the call counts invalid.
uint habuffer_insert_light(vec4 colour) {
  float depth = habuffer_light_gather != 0u ? habuffer_light_depth(gl_FragCoord.z) : -1.0;
  return habuffer_insert(uvec2(gl_FragCoord.xy), depth, ha_pack_rgba(colour));
}

// The same from the light's eye distance of the fragment (-z of its
// light-eye position, interpolated by the host's vertex stage): t =
// (distance - near) / (far - near), the lookup's own operations, so a
// surface's records and its lookups agree to the interpolation's rounding
// (clamped to [0, 1] as above).
uint habuffer_insert_light(vec4 colour, float eye_distance) {
  float t = (eye_distance - habuffer_light_near) / (habuffer_light_far - habuffer_light_near);
  float depth = habuffer_light_gather != 0u ? clamp(t, 0.0, 1.0) : -1.0;
  return habuffer_insert(uvec2(gl_FragCoord.xy), depth, ha_pack_rgba(colour));
}
#else
// Not a light pass: a call fails to compile, naming what is missing.
#define habuffer_insert_light habuffer_insert_light_needs_GlFrameOptions_light
#endif
#endif

// The names hosts called before the library took one prefix (habuffer_) for
// what every technique shares: kept, so a host shader written for them
// compiles unchanged. New code calls habuffer_insert and habuffer_insert_here.
#define ha_insert habuffer_insert
#define ha_insert_here habuffer_insert_here
