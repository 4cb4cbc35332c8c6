// Per-pixel lists kept sorted while inserting (guacamole's PreSortLF, GP5's
// "prelin-cas"), written once for both paths: the same heads, nodes and
// links as lists.glsl (so traversal, compositing and read-back are
// shared), but each fragment is linked in at its place, front to back, by a
// lock-free insertion: walk to the first node not in front of the new entry,
// and compare-and-swap the link that points to it. Nodes are never unlinked
// during a gather and a linked node's entry never changes, so a 32-bit
// compare-and-swap of the link alone is enough (guacamole packs the depth
// with the link into 64 bits to save a read; drivers without 64-bit atomics
// get the same lists): a failed swap means another node was linked right
// there, and the walk goes on from the same link.
//
// Early termination (PreSortLF*): with habuffer_cull_tau > 0, the walk composites
// the nodes it passes (the SPEC's accumulator, acc += (1 - acc) * alpha) and
// stops with HABUFFER_CULLED once acc > tau: the fragment lies behind that much
// opacity, which only grows. Identical entries are kept once (HABUFFER_DUPLICATE),
// as the HA-buffer keeps them.
//
// Host environment provides, besides ha_record.glsl, ha_entries.glsl,
// ha_saturation.glsl and lists.glsl's: uint habuffer_iter_limit (steps of one
// insertion; beyond, HABUFFER_FAILED_ITER), float habuffer_cull_tau, uint
// sl_load_link(uint pixel, uint where) (where 0: the pixel's head, else
// node `where` - 1's link; an acquire read) and uint sl_swap_link(uint
// pixel, uint where, uint expected, uint link) (compare-and-swap with release
// order, so the new node's entry and link are visible before it is; returns
// the link it found).

float sl_alpha(uint data) { return float(data & 255u) * (1.0f / 255.0f); }

uint sl_insert_code(uvec2 p, uint code, uint data) {
  uvec2 e = uvec2(code, data);
  uint pixel = ha_pixel_index(p);
  if (ha_saturated(p, code)) return HABUFFER_SATURATED;
  uint node = 0u;  // the new node (1-based), taken when first needed
  uint where = 0u;
  uint next = sl_load_link(pixel, 0u);
  float acc = 0.0f;
  // Each step passes a node or retries a swap another insertion just won:
  // the total is bounded by the pixel's nodes, but a budget keeps it so.
  for (uint step = 0u; step < habuffer_iter_limit; ++step) {
    if (next != 0u) {
      uvec2 n = ll_load_entry(next - 1u);
      if (n == e) return HABUFFER_DUPLICATE;
      if (ha_entry_before(n, e)) {
        if (habuffer_cull_tau > 0.0f) {
          HABUFFER_PRECISE float next_acc = acc + (1.0f - acc) * sl_alpha(n.y);  // as the CPU path computes it
          acc = next_acc;
          if (acc > habuffer_cull_tau) {
            ha_saturate(p, code);
            return HABUFFER_CULLED;
          }
        }
        where = next;
        next = sl_load_link(pixel, where);
        continue;
      }
    }
    if (node == 0u) {
      uint n = ll_allocate_node();
      if (n >= ll_pool_capacity) return HABUFFER_DROPPED_POOL;
      node = n + 1u;
      ll_store_entry(n, e);
    }
    ll_store_next(node - 1u, next);
    uint found = sl_swap_link(pixel, where, next, node);
    if (found == next) return HABUFFER_STORED;
    next = found;  // a node was linked here meanwhile: it may lie in front
  }
  return HABUFFER_FAILED_ITER;
}

uint sl_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  return sl_insert_code(p, ha_fragment_code(t, coverage), ha_payload_bits == 0u ? 0u : data);
}
