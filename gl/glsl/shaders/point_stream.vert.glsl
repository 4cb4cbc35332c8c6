// The compute entry's form for the blended baselines, whose insert needs the
// fixed-function blender: the stream drawn as one point per fragment, in
// stream order (GL blends the primitives of a draw in order), each at its
// pixel's centre of a screen-sized viewport. The fragment shader reads its
// fragment by index (flat), so the insert sees the stream's own values.
layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer HaStream { HaFragment ha_stream[]; };
flat out uint ha_point_index;

void main() {
  ha_point_index = uint(gl_VertexID);
  HaFragment f = ha_stream[ha_point_index];
  vec2 centre = (vec2(f.x, f.y) + 0.5f) / vec2(habuffer_screen_size);
  gl_Position = vec4(centre * 2.0f - 1.0f, 0.0f, 1.0f);
}
