// The two baselines that store no lists, written once for both paths: each
// fragment is blended into per-pixel accumulators as it arrives (outcome
// HABUFFER_BLENDED), and the resolve turns them into the pixel's colour.
//
// Plain blending ("blend"): the over operator in submission order, unsorted,
// as the fixed-function blender does with (SRC_ALPHA, ONE_MINUS_SRC_ALPHA)
// on colour and (ZERO, ONE_MINUS_SRC_ALPHA) on a transmittance kept in
// alpha: acc = (C, T), C = a c + (1 - a) C, T = (1 - a) T, starting from
// (0, 0, 0, 1). Order-dependent: the floor of time, the ceiling of error.
//
// Weighted blended OIT ("wboit", McGuire and Bavoil 2013): accum += (c a w,
// a w) and revealage *= (1 - a), with the paper's weight function (10),
// w(z, a) = a * max(1e-2, 3e3 * (1 - d(z))^3), d the window depth, here
// normalized to the scene's depth range so the weight spans the scene; the
// resolve is accum.rgb / clamp(accum.a, 1e-4, 5e4) * (1 - revealage) +
// background * revealage. Order-dependent only through float addition.
//
// Host environment provides, besides ha_blend.glsl: float habuffer_depth_near,
// float habuffer_depth_far (the depth range).

// A fragment's term for blend: premultiplied colour and alpha, what the
// GPU's fragment output hands the blender.
vec4 bl_term(vec4 f) { return vec4(f.a * vec3(f), f.a); }

// The blender's equation on that term, (ONE, ONE_MINUS_SRC_ALPHA) on colour
// and (ZERO, ONE_MINUS_SRC_ALPHA) on transmittance: the CPU path's step.
vec4 bl_over(vec4 acc, vec4 f) {
  vec4 s = bl_term(f);
  HABUFFER_PRECISE vec3 rgb = vec3(s) + (1.0f - s.a) * vec3(acc);
  return vec4(rgb, (1.0f - s.a) * acc.a);
}

vec4 bl_finish(vec4 acc, vec3 background) {
  HABUFFER_PRECISE vec3 rgb = vec3(acc) + acc.a * background;
  return vec4(rgb, 1.0f - acc.a);
}

float wb_weight(float t, float alpha) {
  float d = min(max((t - habuffer_depth_near) / (habuffer_depth_far - habuffer_depth_near), 0.0f), 1.0f);
  float k = 1.0f - d;
  return alpha * max(1e-2f, 3e3f * k * k * k);
}

// The accumulation term of one fragment (added to accum) and the factor of
// its revealage (multiplied in).
vec4 wb_accum_term(float t, vec4 f) {
  float w = wb_weight(t, f.a);
  return vec4(vec3(f) * (f.a * w), f.a * w);
}

vec4 wb_finish(vec4 accum, float revealage, vec3 background) {
  vec3 average = vec3(accum) / min(max(accum.a, 1e-4f), 5e4f);
  HABUFFER_PRECISE vec3 rgb = average * (1.0f - revealage) + background * revealage;
  return vec4(rgb, 1.0f - revealage);
}
