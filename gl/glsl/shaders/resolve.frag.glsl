// Resolve pass (SPEC 7): front-to-back traversal and compositing of each
// screen pixel over the background, written to the bound framebuffer.
// The background is one colour, or per pixel from a texture (an opaque
// pass's image, as the guacamole paper composites transparency over it).
uniform vec3 ha_background;
uniform uint ha_background_from_image;
layout(binding = 0) uniform sampler2D ha_background_image;
layout(location = 0) out vec4 ha_color;

void main() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  if (any(greaterThanEqual(p, habuffer_screen_size))) discard;
  vec3 background = ha_background;
  if (ha_background_from_image != 0u) background = texelFetch(ha_background_image, ivec2(p), 0).rgb;
  ha_color = HABUFFER_TECHNIQUE_COMPOSITE(p, background);
}
