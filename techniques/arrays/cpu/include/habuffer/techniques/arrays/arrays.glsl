// Fixed per-pixel arrays (Crassin 2010), written once for both paths: K
// layers per pixel and a per-pixel atomic counter; a fragment beyond the
// K-th of its pixel is dropped and counted (HABUFFER_DROPPED_LAYERS). Sorted after
// the gather (fa_sort_pixel), which leaves in the counter the pixel's sorted
// length, identical entries merged. Layer k of every pixel is contiguous
// (slot k * pixels + pixel), so neighbouring pixels writing their k-th
// fragment touch neighbouring words, as Crassin's 3D texture does.
//
// Host environment provides, besides ha_record.glsl, ha_blend.glsl and
// ha_entries.glsl: uint habuffer_layers (K), uint fa_count_add(uint pixel)
// (atomic; the old count: it keeps counting past K), uint fa_load_count(uint
// pixel), void fa_store_count(uint pixel, uint n), uvec2 fa_load_layer(uint
// slot), void fa_store_layer(uint slot, uvec2 e), and
// void fa_note_overflow(uint arrived) (the host keeps the largest, to size
// the layers of a lossless regather).

uint fa_slot(uint pixel, uint layer) { return layer * (habuffer_screen_size.x * habuffer_screen_size.y) + pixel; }

uint fa_insert_code(uvec2 p, uint code, uint data) {
  uint pixel = ha_pixel_index(p);
  uint k = fa_count_add(pixel);
  if (k >= habuffer_layers) return HABUFFER_DROPPED_LAYERS;
  fa_store_layer(fa_slot(pixel, k), uvec2(code, data));
  return HABUFFER_STORED;
}

uint fa_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  return fa_insert_code(p, ha_fragment_code(t, coverage), ha_payload_bits == 0u ? 0u : data);
}

// Max-heap (the entry that goes last at the root) sift-down within the first n layers.
void fa_sift_down(uint pixel, uint root, uint n) {
  for (;;) {
    uint child = 2u * root + 1u;
    if (child >= n) break;
    uvec2 c = fa_load_layer(fa_slot(pixel, child));
    if (child + 1u < n) {
      uvec2 d = fa_load_layer(fa_slot(pixel, child + 1u));
      if (ha_entry_before(c, d)) {
        child += 1u;
        c = d;
      }
    }
    uvec2 r = fa_load_layer(fa_slot(pixel, root));
    if (!ha_entry_before(r, c)) break;
    fa_store_layer(fa_slot(pixel, root), c);
    fa_store_layer(fa_slot(pixel, child), r);
    root = child;
  }
}

// Heap sort of the first n layers in place, front first: O(n log n) with no
// extra memory, for pixels with more layers than the private array holds.
void fa_heap_sort(uint pixel, uint n) {
  for (uint s = n / 2u; s > 0u; --s) fa_sift_down(pixel, s - 1u, n);
  for (uint end = n - 1u; end > 0u; --end) {
    uvec2 first = fa_load_layer(fa_slot(pixel, 0u));
    fa_store_layer(fa_slot(pixel, 0u), fa_load_layer(fa_slot(pixel, end)));
    fa_store_layer(fa_slot(pixel, end), first);
    fa_sift_down(pixel, 0u, end);
  }
}

// Keeps the first of each run of identical sorted layers, in order; returns how many remain.
uint fa_merge_layers(uint pixel, uint n) {
  uint m = 1u;
  for (uint k = 1u; k < n; ++k) {
    uvec2 e = fa_load_layer(fa_slot(pixel, k));
    if (e != fa_load_layer(fa_slot(pixel, m - 1u))) {
      fa_store_layer(fa_slot(pixel, m), e);
      m += 1u;
    }
  }
  return m;
}

// Sorts pixel p's layers front to back, merges identical ones and leaves the
// sorted length in the counter; returns how many were merged.
uint fa_sort_pixel(uvec2 p) {
  uint pixel = ha_pixel_index(p);
  uint arrived = fa_load_count(pixel);
  if (arrived > habuffer_layers) fa_note_overflow(arrived);
  uint n = arrived > habuffer_layers ? habuffer_layers : arrived;
  if (n == 0u) return 0u;
  uint m = 0u;
  if (n > HABUFFER_SORT_LOCAL) {
    fa_heap_sort(pixel, n);
    m = fa_merge_layers(pixel, n);
  } else {
    for (uint k = 0u; k < n; ++k) ha_local_set(k, fa_load_layer(fa_slot(pixel, k)));
    ha_sort_local(n);
    m = ha_merge_local(n);
    for (uint k = 0u; k < m; ++k) fa_store_layer(fa_slot(pixel, k), ha_local_get(k));
  }
  fa_store_count(pixel, m);
  return n - m;
}

// Composites pixel p's sorted layers over the background.
vec4 fa_composite(uvec2 p, vec3 background) {
  uint pixel = ha_pixel_index(p);
  uint n = fa_load_count(pixel);
  HABUFFER_PIXEL_COLOUR c = ha_pixel_begin();
  for (uint k = 0u; k < n; ++k) {
    uvec2 e = fa_load_layer(fa_slot(pixel, k));
    ha_pixel_under(c, e.x, e.y);
  }
  return ha_pixel_finish(c, background);
}
