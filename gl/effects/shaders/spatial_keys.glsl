// Keys as the host gives them, on the GPU: the domain check, the fold
// (habuffer::spatial::FoldedDomain's, over the block HabufferSpatial) and the
// lookup of one key (sh_spatial.glsl's sh_find_slot), shared by the library's
// find and records passes and by a host shader's habuffer_spatial_find
// (spatial_lookup_part instantiates it with sh_ in place of ha_).

bool sh_in_domain(uvec3 k) { return all(lessThan(k, habuffer_spatial.domain)); }

// FoldedDomain::fold: G = 2^shift slices of a group interleaved along x, the
// groups F to a row. 2D keys (Dz = 1) fold to themselves.
uvec2 sh_fold(uvec3 k) {
  if (habuffer_spatial.domain.z == 1u) return k.xy;
  uint shift = habuffer_spatial.interleave_shift;
  uint group = k.z >> shift;
  uint slice = k.z & ((1u << shift) - 1u);
  uint row = group / habuffer_spatial.slices_per_row;
  uint col = group - row * habuffer_spatial.slices_per_row;
  return uvec2((k.x << shift) + slice + (habuffer_spatial.domain.x << shift) * col,
               k.y + habuffer_spatial.domain.y * row);
}

// Whether key k (any key: one outside the domain is absent) is in the table,
// and its stored value (the rule's encoding; 0 where absent).
bool sh_find(uvec3 k, out uint stored) {
  stored = 0u;
  if (!sh_in_domain(k)) return false;
  uint probes = 0u;
  ha_index s = sh_find_slot(sh_fold(k), probes);
  if (s == ~ha_index(0)) return false;
  sh_word r = sh_load_slot(s);
  if (sh_live(r) == 0u) return false;  // a tombstone
  stored = sh_value(r);
  return true;
}
