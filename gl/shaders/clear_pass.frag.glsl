// Clear pass (SPEC 8, the paper's counting trick): one fragment per slot of a
// tile of the table; fragments of empty slots are discarded, so the
// GL_SAMPLES_PASSED query around the pass counts the stored records. With
// ha_clear_writes 0 the pass only counts.
uniform uvec2 ha_tile_origin;
uniform uint ha_clear_writes;

void main() {
  uvec2 h = ha_tile_origin + uvec2(gl_FragCoord.xy);
  if (any(greaterThanEqual(h, ha_table_size))) discard;
  ha_index s = ha_slot(h);
  if (ha_load_slot(s) == ha_word(0)) discard;
  if (ha_clear_writes != 0u) ha_store_slot(s, ha_word(0));
}
