// What the opaque and the transparent passes share: flat shading of a mesh's
// constant colour, and the paper's depth t, linear eye depth between the near
// and far planes. With R_SHADOWS (translucent shadows, seed 000 section 6)
// the lit colour is multiplied by the light's transmittance T at the
// fragment's world point (light_lookup.glsl, appended before this file):
// colour = lit colour * T, for the opaque pass and every inserted fragment;
// with R_SHADOWS_PCF too, T filtered over 2x2 light pixels.
uniform vec3 r_colour;
uniform float r_opacity;
uniform float r_near;
uniform float r_far;
in vec3 v_eye;
#ifdef R_SHADOWS
in vec3 v_world;
#endif

// v over its largest component's magnitude (zero stays zero): the same
// direction at any scale, so that products of two stay far from float's
// overflow (a mesh at 1e17) and underflow (at 1e-9).
vec3 r_scale_free(vec3 v) {
  float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
  return m > 0.0 ? v / m : v;
}

// The face normal from screen-space derivatives, lit from the eye (either
// side of a face: transparent surfaces show both). The derivatives are
// brought to unit scale first: the shading of a mesh is the same at any
// size (habuffer render of a mesh scaled 1e-17..1e17 equals the unit mesh's).
vec3 r_shaded_colour() {
  vec3 n = cross(r_scale_free(dFdx(v_eye)), r_scale_free(dFdy(v_eye)));
  float len = length(n);
  float facing = len > 0.0 ? abs(n.z) / len : 1.0;
  vec3 lit = r_colour * (0.35 + 0.65 * facing);
#if defined(R_SHADOWS_PCF)
  lit *= habuffer_shadow_transmittance_pcf(v_world);
#elif defined(R_SHADOWS)
  lit *= habuffer_shadow_transmittance(v_world);
#endif
  return lit;
}

float r_depth() { return (-v_eye.z - r_near) / (r_far - r_near); }

// The record's colour word, RGBA8 (R in the high byte): what every gather
// inserts (render's and habuffer-view's).
uint r_pack_rgba(vec3 c, float a) {
  uvec4 b = uvec4(round(clamp(vec4(c, a), 0.0, 1.0) * 255.0));
  return (b.r << 24u) | (b.g << 16u) | (b.b << 8u) | b.a;
}
