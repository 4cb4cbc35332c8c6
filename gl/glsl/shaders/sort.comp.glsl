// The sort pass of the techniques that sort after the gather: one invocation
// per pixel sorts its list front to back and merges identical entries
// (HABUFFER_TECHNIQUE_SORT), adding the merged count to the tallies. Every pixel
// counts its end, and the host expects one per pixel of the screen, so a
// driver that ends invocations early (llvmpipe's loop budget) cannot leave a
// list unsorted unnoticed.
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, habuffer_screen_size))) return;
  uint merged = HABUFFER_TECHNIQUE_SORT(p);
  if (merged != 0u) ha_counter_add(p, HABUFFER_COUNTER_MERGED, merged);
  ha_counter_add(p, HABUFFER_COUNTER_SORT_DONE, 1u);
}
