// The private array the techniques that sort after the gather sort in
// (core/record/include/habuffer/shared/ha_entries.glsl): registers or local memory of one invocation.
uvec2 ha_local[HABUFFER_SORT_LOCAL];
uvec2 ha_local_get(uint k) { return ha_local[k]; }
void ha_local_set(uint k, uvec2 e) { ha_local[k] = e; }
