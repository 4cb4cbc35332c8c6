// What a host shader calls to look up GlSpatialHash's table (after
// spatial_lookup_env.glsl and the sh_ instance of the shared probe, record
// and key sources).

// Whether `key` is in the table, and its stored value: the rule's encoding,
// as GlSpatialHash::find gives it (rule min stores complements); 0 where
// absent. A key outside the domain is absent. The same fold and probe as
// the library's own find pass, so the answers are GlSpatialHash::find's
// and the CPU table's.
bool habuffer_spatial_find(uvec3 key, out uint stored) { return sh_find(key, stored); }

// The same with the value decoded (rule min's complement undone): the value
// SpatialHash::find gives.
bool habuffer_spatial_find_value(uvec3 key, out uint value) {
  bool found = sh_find(key, value);
  if (found && habuffer_spatial.complement != 0u) value = ~value;
  return found;
}
