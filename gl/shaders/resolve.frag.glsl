// Resolve pass (SPEC 7): front-to-back traversal and compositing of each
// screen pixel over the background, written to the bound framebuffer.
uniform vec3 ha_background;
layout(location = 0) out vec4 ha_color;

void main() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  if (any(greaterThanEqual(p, ha_screen_size))) discard;
  ha_color = ha_composite(p, ha_background);
}
