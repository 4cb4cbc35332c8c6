// The k-buffer's insert call for insert_entry.glsl: in the occupancy fill
// pass it only sets its bucket's bit (not an insert call: HABUFFER_UNCOUNTED);
// then the occupancy test, and the insertion through ha_entry.glsl's run
// with deferral (HABUFFER_CARRY_RUN is kb_insert_run).
uint kb_call(uvec2 pixel, float depth, uint coverage, uint rgba) {
  if (habuffer_gather_phase != 0u) {
    kb_fill_fragment(pixel, depth, coverage);
    return HABUFFER_UNCOUNTED;
  }
  if (!ha_fragment_valid(depth, coverage)) return HABUFFER_INVALID;
  if (kb_occupancy_rejects(pixel, ha_depth_code(depth))) return HABUFFER_OCCUPANCY_REJECTED;
  return ha_call_code(pixel, ha_fragment_code(depth, coverage), rgba);
}
