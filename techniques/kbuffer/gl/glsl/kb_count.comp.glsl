// The k-buffer's count pass (seed 003): one invocation per pixel finds the
// bucket of its k-th occupied bit, the limit the insertion rejects beyond.
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, habuffer_screen_size))) return;
  kb_count_pixel(p);
}
