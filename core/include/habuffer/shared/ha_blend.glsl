// Front-to-back compositing of SPEC 7, shared by every technique (the same
// float32 operations in the same order, so exact techniques give identical
// images), written once for both paths.

vec4 ha_unpack_rgba(uint data) {
  return vec4(float(data >> 24u), float((data >> 16u) & 255u), float((data >> 8u) & 255u),
              float(data & 255u)) * (1.0f / 255.0f);
}

// Straight-alpha front-to-back "under" operator, float32.
// HABUFFER_PRECISE (GLSL's precise) keeps every multiply and add apart, as
// the C++ side computes them.
vec4 ha_blend_under(vec4 c, vec4 f) {
  HABUFFER_PRECISE float w = (1.0f - c.a) * f.a;
  HABUFFER_PRECISE vec3 rgb = vec3(c) + w * vec3(f);
  HABUFFER_PRECISE float a = c.a + w;
  return vec4(rgb, a);
}

vec4 ha_finish(vec4 c, vec3 background) {
  HABUFFER_PRECISE vec3 rgb = vec3(c) + (1.0f - c.a) * background;
  return vec4(rgb, c.a);
}
