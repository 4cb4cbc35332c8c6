// 2x2 percentage-closer filtering of translucent shadows' T (--shadow-filter
// pcf), written once for both paths: core/effects/src/transmittance.cpp's
// transmittance_pcf and gl/glsl/shaders/light_lookup.glsl's
// habuffer_shadow_transmittance_pcf (under the prefix hs_).

// The light pixels whose centres surround window position `w` on a map of
// `size` pixels, `lo` and `hi` per axis (clamped to the map), and `f`, the
// weight of `hi` along each axis.
void ha_pcf_taps(vec2 w, uvec2 size, HABUFFER_INOUT(uvec2) lo, HABUFFER_INOUT(uvec2) hi, HABUFFER_INOUT(vec2) f) {
  float gx = max(w.x - 0.5f, 0.0f);
  float gy = max(w.y - 0.5f, 0.0f);
  lo = uvec2(min(uint(gx), size.x - 1u), min(uint(gy), size.y - 1u));
  hi = uvec2(min(lo.x + 1u, size.x - 1u), min(lo.y + 1u, size.y - 1u));
  f = vec2(gx - float(lo.x), gy - float(lo.y));
}

// The four taps' T weighted bilinearly (t10 at hi.x, lo.y; t01 at lo.x,
// hi.y). precise: the same products on every GPU as on the CPU.
float ha_pcf_blend(float t00, float t10, float t01, float t11, vec2 f) {
  HABUFFER_PRECISE float low = t00 * (1.0f - f.x) + t10 * f.x;
  HABUFFER_PRECISE float high = t01 * (1.0f - f.x) + t11 * f.x;
  HABUFFER_PRECISE float t = low * (1.0f - f.y) + high * f.y;
  return t;
}
