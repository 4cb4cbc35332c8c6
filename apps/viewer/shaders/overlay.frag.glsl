#version 450 core
// A heat map over the view: one value a pixel (fragments, culled fragments
// or max age: a word each, v_stride words apart from v_first), scaled by
// v_scale into a blue-to-red ramp, blended at v_alpha where non-zero.
layout(std430, binding = 0) readonly buffer VValues { uint v_values[]; };
uniform uvec2 v_screen;
uniform uint v_first;
uniform uint v_stride;
uniform float v_scale;
uniform float v_alpha;
in vec2 v_uv;
layout(location = 0) out vec4 v_out;

vec3 v_ramp(float x) {
  return clamp(vec3(1.5 - abs(4.0 * x - 3.0), 1.5 - abs(4.0 * x - 2.0), 1.5 - abs(4.0 * x - 1.0)), 0.0, 1.0);
}

void main() {
  uvec2 p = min(uvec2(v_uv * vec2(v_screen)), v_screen - 1u);
  uint v = v_values[v_first + v_stride * (p.x + p.y * v_screen.x)];
  if (v == 0u) discard;
  v_out = vec4(v_ramp(clamp(float(v) * v_scale, 0.0, 1.0)), v_alpha);
}
