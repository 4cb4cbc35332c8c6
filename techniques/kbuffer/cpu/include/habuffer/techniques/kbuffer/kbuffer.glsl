// The k-buffer (the k nearest fragments of each pixel; Vasilakis and
// Papaioannou 2015 improve it with occupancy maps), written once for both
// paths. Insertion by atomic max (the HA-buffer's mechanism, without
// hashing): a pixel's K layers are slots (layer-major), a record walks them
// front to back, each slot keeping the larger of what it held and what
// arrives and passing the smaller on; what leaves the K-th layer is dropped
// (HABUFFER_DROPPED_LAYERS). Every slot only grows, so at any time the layers hold
// the K largest records that reached them, in order: the K nearest entries,
// sorted, without a sort pass. Records are SPEC 2 records with age 1 (never
// 0, so 0 is an empty slot), comparing by (code, data) as every technique's
// entries do. An insert call carries a HabufferCarry (a = layer + 1), so the GPU
// path defers and resumes a call cut short as it does the HA-buffer's.
//
// Occupancy-map culling (seed 003): a fill pass sets one bit per occupied
// depth bucket (32 * kb_occupancy_words buckets per pixel over the scene's
// depth range), a count pass finds the bucket of the k-th occupied bit, and
// the insertion rejects fragments in buckets beyond it (HABUFFER_OCCUPANCY_REJECTED):
// at least k fragments lie in front (each occupied bucket holds one), so
// the k nearest are never rejected (the paper's Lemma 2.1). Buckets divide
// depth codes with integers, so both paths reject the same fragments.
//
// Host environment provides, besides ha_record.glsl, ha_carry.glsl and
// ha_blend.glsl: uint habuffer_layers (K), uvec2 habuffer_screen_size, the slot atomics
// of ha_insert.glsl's environment (ha_atomic_max_slot, ha_atomic_missed,
// ha_load_slot), uint kb_occupancy_culling (0: off), uint kb_occupancy_words, uint
// kb_occupancy_near_code, uint kb_occupancy_bucket_codes, void
// kb_or_occupancy(uint word, uint bits) (atomic or), uint
// kb_load_occupancy(uint word), uint kb_load_limit(uint pixel), void
// kb_store_limit(uint pixel, uint bucket), uint ha_lowest_bit(uint w)
// (index of the lowest set bit of a non-zero word).

uint kb_pixel(uvec2 p) { return p.x + p.y * habuffer_screen_size.x; }
ha_index kb_slot(uint pixel, uint layer) { return ha_index(layer) * ha_index(habuffer_screen_size.x * habuffer_screen_size.y) + ha_index(pixel); }

// --- occupancy map ----------------------------------------------------------
uint kb_buckets() { return 32u * kb_occupancy_words; }

uint kb_bucket(uint code) {
  uint nearer = kb_occupancy_near_code - min(code, kb_occupancy_near_code);
  return min(nearer / kb_occupancy_bucket_codes, kb_buckets() - 1u);
}

// Fill pass: the bucket of one fragment.
void kb_fill(uvec2 p, uint code) {
  uint b = kb_bucket(code);
  kb_or_occupancy(kb_pixel(p) * kb_occupancy_words + b / 32u, 1u << (b & 31u));
}

// The fill step of one fragment on every path: an invalid fragment (by
// depth, or a mask of no sample) fills nothing; the map reads the depth
// code alone.
void kb_fill_fragment(uvec2 p, float t, uint coverage) {
  if (ha_fragment_valid(t, coverage)) kb_fill(p, ha_depth_code(t));
}

// Count pass: the bucket holding the k-th occupied bit of pixel p (nearest
// first), or kb_buckets() when fewer than K buckets are occupied (nothing is
// rejected). O(K) bit clears (Kernighan), as the paper counts.
void kb_count_pixel(uvec2 p) {
  uint pixel = kb_pixel(p);
  uint seen = 0u;
  uint limit = kb_buckets();
  for (uint w = 0u; w < kb_occupancy_words && limit == kb_buckets(); ++w) {
    uint bits = kb_load_occupancy(pixel * kb_occupancy_words + w);
    while (bits != 0u) {
      seen += 1u;
      if (seen == habuffer_layers) {
        limit = w * 32u + ha_lowest_bit(bits);
        break;
      }
      bits &= bits - 1u;
    }
  }
  kb_store_limit(pixel, limit);
}

bool kb_occupancy_rejects(uvec2 p, uint code) {
  return kb_occupancy_culling != 0u && kb_bucket(code) > kb_load_limit(kb_pixel(p));
}

// --- insertion ---------------------------------------------------------------
// One layer: HABUFFER_PENDING while the carried record goes on to the next layer
// (or tries the same one again: an emulated atomic found it busy), HABUFFER_CUT
// when that atomic gave up, else the call's outcome.
uint kb_insert_step(HABUFFER_INOUT(HabufferCarry) c) {
  if (c.a > habuffer_layers) return HABUFFER_DROPPED_LAYERS;
  ha_index s = kb_slot(kb_pixel(c.p), c.a - 1u);
  // Slots only grow: a larger value read is larger still (no atomic needed).
  if (ha_high(ha_load_slot(s)) > ha_high(c.r)) {
    c.iter += 1u;
    c.a += 1u;
    return HABUFFER_PENDING;
  }
  ha_word old = ha_atomic_max_slot(s, c.r);
  uint missed = ha_atomic_missed();
  if (missed != 0u) return missed;
  c.iter += 1u;
  if (old == c.r) return HABUFFER_DUPLICATE;
  if (old < c.r) {
    if (old == ha_word(0)) return HABUFFER_STORED;
    c.r = old;  // the displaced record goes on behind
  }
  c.a += 1u;
  return HABUFFER_PENDING;
}

uint kb_insert_run(HABUFFER_INOUT(HabufferCarry) c) {
  uint outcome = HABUFFER_PENDING;
  while (outcome == HABUFFER_PENDING) outcome = kb_insert_step(c);
  return outcome;
}

// The whole insert call on the CPU path (the occupancy test included; the
// fill and count passes are the host's).
// The occupancy map reads the depth code alone (the fill pass's), the record
// carries the coverage too.
uint kb_insert_fragment(uvec2 p, float t, uint coverage, uint data) {
  if (!ha_fragment_valid(t, coverage)) return HABUFFER_INVALID;
  if (kb_occupancy_rejects(p, ha_depth_code(t))) return HABUFFER_OCCUPANCY_REJECTED;
  HabufferCarry c = habuffer_carry_begin(p, ha_fragment_code(t, coverage), data);
  return kb_insert_run(c);
}

// Pixel p's layers, nearest first, until the first empty one.
uint kb_length(uvec2 p) {
  uint pixel = kb_pixel(p);
  uint n = 0u;
  while (n < habuffer_layers && ha_load_slot(kb_slot(pixel, n)) != ha_word(0)) n += 1u;
  return n;
}

vec4 kb_composite(uvec2 p, vec3 background) {
  uint pixel = kb_pixel(p);
  HABUFFER_PIXEL_COLOUR c = ha_pixel_begin();
  for (uint k = 0u; k < habuffer_layers; ++k) {
    ha_word r = ha_load_slot(kb_slot(pixel, k));
    if (r == ha_word(0)) break;
    ha_pixel_under(c, ha_code(r), ha_data(r));
  }
  return ha_pixel_finish(c, background);
}
