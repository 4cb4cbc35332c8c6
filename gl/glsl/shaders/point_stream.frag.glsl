// One stream fragment's insert (point_stream.vert.glsl).
layout(std430, binding = HABUFFER_BINDING_STREAM) readonly buffer HaStream { HaFragment ha_stream[]; };
flat in uint ha_point_index;

void main() {
  HaFragment f = ha_stream[ha_point_index];
  habuffer_insert(uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
}
