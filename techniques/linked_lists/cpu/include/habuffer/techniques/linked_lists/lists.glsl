// Per-pixel linked lists (Yang, Hensley, Grün, Thibieroz 2010), written once
// for both paths: a head-pointer image, a node pool with one atomic counter,
// each fragment appended with one atomic exchange; sorted after the gather
// (ll_sort_pixel) and composited front to back. Nodes hold the SPEC 2 depth
// code and the data word (0 for L32), so sorted lists compare bit for bit
// with the HA-buffer's.
//
// Links are 1-based node numbers, 0 ending a list, so a zeroed head image is
// empty; node n is stored at index n - 1.
// Host environment provides, besides ha_record.glsl, ha_blend.glsl and
// ha_entries.glsl: uint ll_pool_capacity (nodes), uint ll_allocate_node()
// (a free node, or ll_pool_capacity or more when the pool has none left: on
// the GPU the counter's old value, atomically incremented, which keeps
// counting past the capacity, so the host learns how many nodes a frame
// wanted; on the CPU the next node of the thread's block, node_blocks.h),
// uint ll_exchange_head(uint pixel, uint link) (atomic; the old head),
// uint ll_load_head(uint pixel), void ll_store_head(uint pixel, uint link),
// uvec2 ll_load_entry(uint node), void ll_store_entry(uint node, uvec2 e),
// uint ll_load_next(uint node), void ll_store_next(uint node, uint link).

uint ll_insert_code(uvec2 p, uint code, uint data) {
  uint n = ll_allocate_node();
  if (n >= ll_pool_capacity) return HABUFFER_DROPPED_POOL;
  ll_store_entry(n, uvec2(code, data));
  ll_store_next(n, ll_exchange_head(ha_pixel_index(p), n + 1u));
  return HABUFFER_STORED;
}

// The whole insert call of one fragment (identical entries are merged when
// the lists are sorted, and counted as duplicates then).
uint ll_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  return ll_insert_code(p, ha_fragment_code(t, coverage), ha_payload_bits == 0u ? 0u : data);
}

uint ll_length(uint head) {
  uint n = 0u;
  for (uint l = head; l != 0u; l = ll_load_next(l - 1u)) n += 1u;
  return n;
}

// Cuts the list starting at `l` after `count` (at least 1) nodes; returns the rest.
uint ll_split(uint l, uint count) {
  if (l == 0u) return 0u;
  for (uint k = 1u; k < count && ll_load_next(l - 1u) != 0u; ++k) l = ll_load_next(l - 1u);
  uint rest = ll_load_next(l - 1u);
  ll_store_next(l - 1u, 0u);
  return rest;
}

// Bottom-up merge sort of a list of n nodes in place (links rewritten, no
// extra memory, no recursion), stable; returns the new head.
uint ll_merge_sort(uint head, uint n) {
  for (uint width = 1u; width < n; width *= 2u) {
    uint rest = head;
    uint tail = 0u;
    head = 0u;
    while (rest != 0u) {
      uint a = rest;
      uint b = ll_split(a, width);
      rest = ll_split(b, width);
      while (a != 0u || b != 0u) {
        uint take = a;
        if (b != 0u && (a == 0u || ha_entry_before(ll_load_entry(b - 1u), ll_load_entry(a - 1u)))) take = b;
        if (take == a) a = ll_load_next(a - 1u);
        else b = ll_load_next(b - 1u);
        if (tail == 0u) head = take;
        else ll_store_next(tail - 1u, take);
        tail = take;
      }
    }
    ll_store_next(tail - 1u, 0u);
  }
  return head;
}

// Unlinks every node equal to the one before it in a sorted list; returns how many.
uint ll_merge_duplicates(uint head) {
  uint merged = 0u;
  uint l = head;
  while (l != 0u) {
    uint next = ll_load_next(l - 1u);
    if (next != 0u && ll_load_entry(next - 1u) == ll_load_entry(l - 1u)) {
      ll_store_next(l - 1u, ll_load_next(next - 1u));
      merged += 1u;
    } else {
      l = next;
    }
  }
  return merged;
}

// Sorts pixel p's list front to back and merges identical entries; returns
// how many were merged. Short lists go through the private array (their
// sorted entries rewritten into the list's first nodes, the rest cut off).
uint ll_sort_pixel(uvec2 p) {
  uint pixel = ha_pixel_index(p);
  uint head = ll_load_head(pixel);
  uint n = ll_length(head);
  if (n > HABUFFER_SORT_LOCAL) {
    head = ll_merge_sort(head, n);
    ll_store_head(pixel, head);
    return ll_merge_duplicates(head);
  }
  uint l = head;
  for (uint k = 0u; k < n; ++k) {
    ha_local_set(k, ll_load_entry(l - 1u));
    l = ll_load_next(l - 1u);
  }
  ha_sort_local(n);
  uint m = ha_merge_local(n);
  l = head;
  uint last = 0u;
  for (uint k = 0u; k < m; ++k) {
    ll_store_entry(l - 1u, ha_local_get(k));
    last = l;
    l = ll_load_next(l - 1u);
  }
  if (last != 0u) ll_store_next(last - 1u, 0u);
  return n - m;
}

// Composites pixel p's sorted list over the background.
vec4 ll_composite(uvec2 p, vec3 background) {
  HABUFFER_PIXEL_COLOUR c = ha_pixel_begin();
  for (uint l = ll_load_head(ha_pixel_index(p)); l != 0u; l = ll_load_next(l - 1u)) {
    uvec2 e = ll_load_entry(l - 1u);
    ha_pixel_under(c, e.x, e.y);
  }
  return ha_pixel_finish(c, background);
}
