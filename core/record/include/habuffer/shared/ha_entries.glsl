// A pixel's fragments as entries (depth code, data) for the techniques that
// sort after insertion (linked lists, fixed arrays), written once for both
// paths: the order the HA-buffer's traversal gives (its records compare by
// code, then data: larger is nearer), sorting in a private array and merging
// identical entries, which the HA-buffer stores once.
//
// Host environment provides: uvec2 habuffer_screen_size, and a private array of
// HABUFFER_SORT_LOCAL entries through uvec2 ha_local_get(uint k) and
// void ha_local_set(uint k, uvec2 e).

uint ha_pixel_index(uvec2 p) { return p.x + p.y * habuffer_screen_size.x; }

// Whether entry a lies in front of entry b in a pixel's list.
bool ha_entry_before(uvec2 a, uvec2 b) { return a.x > b.x || (a.x == b.x && a.y > b.y); }

// Stable insertion sort of the first n (at most HABUFFER_SORT_LOCAL) private entries.
void ha_sort_local(uint n) {
  for (uint k = 1u; k < n; ++k) {
    uvec2 e = ha_local_get(k);
    uint j = k;
    while (j > 0u && ha_entry_before(e, ha_local_get(j - 1u))) {
      ha_local_set(j, ha_local_get(j - 1u));
      j -= 1u;
    }
    ha_local_set(j, e);
  }
}

// Keeps the first of each run of identical entries among the first n sorted
// private entries, in order; returns how many remain.
uint ha_merge_local(uint n) {
  if (n == 0u) return 0u;
  uint m = 1u;
  for (uint k = 1u; k < n; ++k) {
    uvec2 e = ha_local_get(k);
    if (e != ha_local_get(m - 1u)) {
      ha_local_set(m, e);
      m += 1u;
    }
  }
  return m;
}
