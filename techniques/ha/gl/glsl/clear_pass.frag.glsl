// Clear pass (SPEC 8, the paper's counting trick): one fragment per slot of a
// tile of the table; fragments of empty slots are discarded, so the
// GL_SAMPLES_PASSED query around the pass counts the stored records. With
// ha_clear_writes 0 the pass only counts. With ha_clear_atomic_count 1 (a
// host's occlusion query is active) each stored record adds 1 to
// ha_clear_count instead and every fragment is discarded, after its store
// (side effects before discard stay), so the host's query counts none.
uniform uvec2 ha_tile_origin;
uniform uint ha_clear_writes;
uniform uint ha_clear_atomic_count;
layout(std430, binding = HABUFFER_BINDING_STREAM) buffer HaClearCount { uint ha_clear_count[2]; };

void main() {
  uvec2 h = ha_tile_origin + uvec2(gl_FragCoord.xy);
  if (any(greaterThanEqual(h, ha_table_size))) discard;
  ha_index s = ha_slot(h);
  if (ha_load_slot(s) == ha_word(0)) discard;
  if (ha_clear_writes != 0u) ha_store_slot(s, ha_word(0));
  if (ha_clear_atomic_count != 0u) {
    atomicAdd(ha_clear_count[0], 1u);
    discard;
  }
}
