// Paged per-pixel lists (seed 000, Table 1 and 2's "paged lists"), written
// once for both paths: the linked lists of lists.glsl (head image, node
// pool of (code, data) entries and links, sorted after the gather by
// ll_sort_pixel and composited by ll_composite), but nodes are taken in
// pages of HABUFFER_PAGE_NODES consecutive nodes per pixel, so a pixel's
// nodes lie together and the pool's counter is hit once per page, not once
// per fragment.
//
// A head is the pixel's last linked node + 1 (0: empty), so node n lies in
// page n / HABUFFER_PAGE_NODES, and a head h that is not a multiple of the
// page size says that node h (the next of its page) is free: the pixel's
// pages are its own, every page but the head's is full, and the head's is
// filled up to the head. An insertion swaps the head to h + 1 (the page has
// room) or to a fresh page's first node + 1 (a page counter add), linking
// the old head; a failed swap (another invocation linked a node to this
// pixel) retries with the head it found, keeping a page it allocated for a
// later try of the same call. No invocation waits for another; every try
// either links a node or sees another one linked, and habuffer_iter_limit bounds
// the tries (HABUFFER_FAILED_ITER beyond). A page allocated and left unused
// (the pixel's page got room meanwhile, or the tries ran out) is counted
// (pl_waste_page), so requested nodes = linked nodes + the unused rest of
// head pages + wasted pages.
//
// The sort rewrites links (ll_merge_sort) and unlinks duplicates, so after
// it pl_head_to_top makes the list start at its highest node again: the
// nodes after it in its page are then not on any list, and a later insert
// call (the CPU path's next batch) may take them.
//
// Host environment provides, besides ha_record.glsl, ha_blend.glsl,
// ha_entries.glsl and lists.glsl's (whose ll_allocate_node and
// ll_exchange_head these functions do not call): uint ll_pool_capacity
// (nodes; pages are its first floor(capacity / HABUFFER_PAGE_NODES) blocks
// of HABUFFER_PAGE_NODES), uint habuffer_iter_limit, uint pl_load_head(uint pixel)
// (a read of a head other invocations may swap), uint pl_swap_head(uint
// pixel, uint expected, uint link) (compare-and-swap; returns the head it
// found), uint pl_allocate_page() (atomically adds HABUFFER_PAGE_NODES to the
// node counter and returns its old value, the page's first node: the counter
// counts on past the capacity, so the host learns the nodes a gather asked
// for), void pl_waste_page() (counts a page allocated and never linked).
#ifndef HABUFFER_PAGE_NODES
#define HABUFFER_PAGE_NODES 4u
#endif
#define HABUFFER_NO_PAGE 0xFFFFFFFFu

uint pl_insert_code(uvec2 p, uint code, uint data) {
  uint pixel = ha_pixel_index(p);
  uint page = HABUFFER_NO_PAGE;  // the first node of a page this call allocated and has not linked
  uint head = pl_load_head(pixel);
  for (uint attempt = 0u; attempt < habuffer_iter_limit; ++attempt) {
    bool room = head != 0u && head % HABUFFER_PAGE_NODES != 0u;
    if (!room && page == HABUFFER_NO_PAGE) {
      page = pl_allocate_page();
      if (page >= ll_pool_capacity || ll_pool_capacity - page < HABUFFER_PAGE_NODES) return HABUFFER_DROPPED_POOL;
    }
    uint node = room ? head : page;
    uint found = pl_swap_head(pixel, head, node + 1u);
    if (found == head) {
      ll_store_entry(node, uvec2(code, data));
      ll_store_next(node, head);
      if (room && page != HABUFFER_NO_PAGE) pl_waste_page();
      return HABUFFER_STORED;
    }
    head = found;  // another node was linked meanwhile: its page may have room
  }
  if (page != HABUFFER_NO_PAGE) pl_waste_page();
  return HABUFFER_FAILED_ITER;
}

// The whole insert call of one fragment (identical entries are merged when
// the lists are sorted, and counted as duplicates then).
uint pl_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  return pl_insert_code(p, ha_fragment_code(t, coverage), ha_payload_bits == 0u ? 0u : data);
}

// Makes the pixel's list start at its highest node, keeping the order of its
// entries: the first node and the highest swap places (and entries).
void pl_head_to_top(uint pixel) {
  uint first = ll_load_head(pixel);
  if (first == 0u) return;
  uint top = first;
  uint before_top = 0u;  // the node linking to top
  uint prev = first;
  uint l = ll_load_next(first - 1u);
  while (l != 0u) {
    if (l > top) {
      top = l;
      before_top = prev;
    }
    prev = l;
    l = ll_load_next(l - 1u);
  }
  if (top == first) return;
  uvec2 e = ll_load_entry(first - 1u);
  ll_store_entry(first - 1u, ll_load_entry(top - 1u));
  ll_store_entry(top - 1u, e);
  uint after_first = ll_load_next(first - 1u);
  uint after_top = ll_load_next(top - 1u);
  if (before_top == first) {
    ll_store_next(top - 1u, first);  // first, top, rest: top, first, rest
  } else {
    ll_store_next(top - 1u, after_first);
    ll_store_next(before_top - 1u, first);
  }
  ll_store_next(first - 1u, after_top);
  ll_store_head(pixel, top);
}

// Sorts pixel p's list front to back (ll_sort_pixel), merging identical
// entries, and starts it at its highest node; returns how many were merged.
uint pl_sort_pixel(uvec2 p) {
  uint merged = ll_sort_pixel(p);
  pl_head_to_top(ha_pixel_index(p));
  return merged;
}
