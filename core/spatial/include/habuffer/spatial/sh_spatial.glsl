// The spatial hash of spatial_hash.h, written once for both paths: coherent
// Robin Hood hashing of integer keys in a domain larger than the table.
//
// Record (64 bits, compared as an unsigned integer):
//   | age (A bits) | quotient (31 - A bits) | live (1) | value (32) |
// The key k = (u, v) of the (folded) 2D domain is split into its table
// position p = (u mod Hx, v mod Hy) and its quotient
// q = u / Hx + qx * (v / Hy), qx = ceil(Du / Hx). Age equivalence (SPEC 4)
// gives p back from a record's slot and age; the quotient is the rest of the
// key, so (slot, age, quotient) names one key (docs/spec-notes.md, "The
// spatial hash", proves it). The record's key bits are age and quotient:
// records of different keys are ordered by them alone, so the value and the
// live bit decide only between two records of one key, which the insert
// merges by the rule (the larger record wins: the container encodes its
// rules as "larger is kept"). An erased key leaves its key bits with live 0
// and value 0 (a tombstone): every other record compares with it as with the
// key, so lookups and inserts see the same table, and the key inserted again
// replaces it.
//
// Host environment provides what shared/ha_probe.glsl needs (uvec2
// ha_table_size (H), ha_offset(i) (O[i]), ha_div_block(v), ha_max_age_cells_x,
// the slot index type ha_index), and: type sh_word (64-bit unsigned), uint
// sh_age_bits, uint sh_quotient_x (qx), uint sh_iter_limit,
// sh_word sh_atomic_max_slot(ha_index s, sh_word r) (returns the old value),
// uint sh_atomic_missed() (0 when the last slot atomic happened; else HABUFFER_SH_PENDING
// or HABUFFER_SH_CUT, see sh_insert_step; always 0 where atomics are native),
// sh_word sh_load_slot(ha_index s), void sh_atomic_max_age(uint cell, uint a),
// uint sh_load_max_age(uint cell), sh_word sh_word_of(uint high, uint low),
// uint sh_high(sh_word r), uint sh_low(sh_word r), HABUFFER_INOUT(T);
// for the miss filter: uint sh_filter_blocks_x (filter blocks per row; 0:
// the table has no filter), uint sh_filter_shift_y (log2 of a block's
// height), uint sh_load_filter(ha_index w) and, where
// records are inserted, void sh_atomic_or_filter(ha_index w, uint bits).

uint sh_max_age() { return (1u << sh_age_bits) - 1u; }
uint sh_quotient_bits() { return 31u - sh_age_bits; }
uint sh_max_quotient() { return (1u << sh_quotient_bits()) - 1u; }

sh_word sh_pack(uint age, uint q, uint live, uint value) {
  return sh_word_of((age << (32u - sh_age_bits)) | (q << 1u) | live, value);
}
uint sh_age(sh_word r) { return sh_high(r) >> (32u - sh_age_bits); }
uint sh_quotient(sh_word r) { return (sh_high(r) >> 1u) & sh_max_quotient(); }
uint sh_live(sh_word r) { return sh_high(r) & 1u; }
uint sh_value(sh_word r) { return sh_low(r); }
// The key bits: age and quotient (the high word without the live bit).
uint sh_key_bits(sh_word r) { return sh_high(r) >> 1u; }
sh_word sh_with_age(sh_word r, uint age) {
  uint keep = (1u << (32u - sh_age_bits)) - 1u;
  return sh_word_of((sh_high(r) & keep) | (age << (32u - sh_age_bits)), sh_low(r));
}
// The erased key's marker: its key bits, live 0, value 0.
sh_word sh_tombstone(sh_word r) { return sh_word_of(sh_high(r) & 0xFFFFFFFEu, 0u); }

// Table position and quotient of key k (in the folded 2D domain).
uvec2 sh_position(uvec2 k) {
  return uvec2(k.x - sh_div_hx(k.x) * ha_table_size.x, k.y - sh_div_hy(k.y) * ha_table_size.y);
}
uint sh_key_quotient(uvec2 k) { return sh_div_hx(k.x) + sh_quotient_x * sh_div_hy(k.y); }
// The key back from its position and quotient.
uvec2 sh_key(uvec2 p, uint q) {
  return uvec2(p.x + (q % sh_quotient_x) * ha_table_size.x, p.y + (q / sh_quotient_x) * ha_table_size.y);
}

// Coherent probing (SPEC 3), age equivalence (SPEC 4), the slot index and
// the max-age cell are the HA-buffer's own, over positions in place of
// pixels: ha_probe, ha_owner, ha_slot, ha_cell (shared/ha_probe.glsl, which
// the host includes before this file).

// The key of the record `r` found in slot `s` (age equivalence gives its
// position, the quotient the rest): iteration, loading, rebuilding.
uvec2 sh_record_key(ha_index s, sh_word r) {
  uvec2 h = uvec2(uint(s % ha_index(ha_table_size.x)), uint(s / ha_index(ha_table_size.x)));
  return sh_key(ha_owner(h, sh_age(r)), sh_quotient(r));
}

// The miss filter (issue 36). A lookup of an absent key walked its ages
// until a younger slot: two or three slots at random places at load 0.95.
// The filter answers most such lookups from one 32-bit word. The table's
// positions are cut into blocks 8 wide and 2^sh_filter_shift_y high (4 at
// 16 bits a position, 8 at 8 bits); each block owns 16 words (one 64-byte
// line), blocks row-major, so neighbouring keys read the same line. A
// position's place in its block picks its word (2 places a word at 16 bits,
// 4 at 8). The word's low 16 bits are the places' own fields of e bits
// (e = 8 or 4), its high 16 bits are shared. Key (p, q) sets 4 bits of its
// word: bit fold(q) mod e of its place's field, where fold xors q's groups
// of log2(e) bits, so quotients below e never share it and no other place
// sets it (where the domain has at most e quotients, every miss is answered
// here), and 3 bits of the shared half from a hash of place and quotient.
// Every insert call sets them (an atomic or: the words are the same for
// every order and thread count) before its first probe. A lookup finding one
// of its bits clear ends there: the key was never inserted since the table
// was made or cleared. The filter holds the keys of every record in the
// table and possibly more (keys whose records were pushed out: dropped
// tombstones, lost keys), so it only ever turns a walk into an early
// "absent": no answer depends on it.
// log2(places a word): 1 at 16 bits a position, 2 at 8.
uint sh_filter_places_log2() { return sh_filter_shift_y - 1u; }
// Position p's place in its block, x fastest.
uint sh_filter_place(uvec2 p) {
  return (p.x & ((1u << HABUFFER_SH_FILTER_SHIFT_X) - 1u)) |
         ((p.y & ((1u << sh_filter_shift_y) - 1u)) << HABUFFER_SH_FILTER_SHIFT_X);
}
// The word of position p in the filter.
ha_index sh_filter_word(uvec2 p) {
  ha_index block = ha_index(p.x >> HABUFFER_SH_FILTER_SHIFT_X) +
                   ha_index(p.y >> sh_filter_shift_y) * ha_index(sh_filter_blocks_x);
  return block * ha_index(HABUFFER_SH_FILTER_WORDS) + ha_index(sh_filter_place(p) >> sh_filter_places_log2());
}
// Key (p, q)'s bits in that word (four bit numbers; the hashed ones may coincide).
uint sh_filter_bits(uvec2 p, uint q) {
  uint place = sh_filter_place(p);
  uint g = 4u - sh_filter_places_log2();  // log2(e): 3 or 2
  uint f = q;
  f ^= f >> (8u * g);
  f ^= f >> (4u * g);
  f ^= f >> (2u * g);
  f ^= f >> g;
  uint own = ((place & ((1u << sh_filter_places_log2()) - 1u)) << g) + (f & ((1u << g) - 1u));
  uint h = q + place * 0x9E3779B9u;
  // A 32-bit finaliser (Wellons' lowbias32): each hashed bit number depends
  // on every bit of q and of the place.
  h ^= h >> 16u;
  h *= 0x7FEB352Du;
  h ^= h >> 15u;
  h *= 0x846CA68Bu;
  h ^= h >> 16u;
  return (1u << own) | (1u << (16u + (h & 15u))) | (1u << (16u + ((h >> 4u) & 15u))) |
         (1u << (16u + ((h >> 8u) & 15u)));
}
// Whether key (p, q) may be in the table (false: it is not).
bool sh_filter_may_hold(uvec2 p, uint q) {
  if (sh_filter_blocks_x == 0u) return true;
  uint bits = sh_filter_bits(p, q);
  return (sh_load_filter(sh_filter_word(p)) & bits) == bits;
}

// The insert (host environments that only look up, such as a host shader's
// lookup over read-only buffers, define HABUFFER_SH_LOOKUP_ONLY and need no
// atomics).
#ifndef HABUFFER_SH_LOOKUP_ONLY
// One insert call between probes.
struct ShCarry {
  uvec2 p;    // position of the carried record's key
  uint a;     // age about to be tried
  uint iter;  // probes made
  sh_word r;  // the carried record, with age a while a <= AMAX
};

ShCarry sh_carry_begin(uvec2 k, uint live, uint value) {
  ShCarry c;
  c.p = sh_position(k);
  c.a = 1u;
  c.iter = 0u;
  c.r = sh_pack(1u, sh_key_quotient(k), live, value);
  return c;
}

// The key of the record a call carries (the failed one's, handed back).
uvec2 sh_carry_key(ShCarry c) { return sh_key(c.p, sh_quotient(c.r)); }

// One probe: HABUFFER_SH_PENDING while a record must go on, else the call's outcome.
uint sh_insert_step(HABUFFER_INOUT(ShCarry) c) {
  // The call's key joins the miss filter before its first probe (a step
  // an emulated atomic repeats sets the same bits again).
  if (c.iter == 0u && sh_filter_blocks_x != 0u)
    sh_atomic_or_filter(sh_filter_word(c.p), sh_filter_bits(c.p, sh_quotient(c.r)));
  if (c.a > sh_max_age()) return sh_live(c.r) != 0u ? HABUFFER_SH_FAILED_AGE : HABUFFER_SH_STORED_TOMBSTONE_DROPPED;
  if (c.iter >= sh_iter_limit) return sh_live(c.r) != 0u ? HABUFFER_SH_FAILED_ITER : HABUFFER_SH_STORED_TOMBSTONE_DROPPED;
  uvec2 h = ha_probe(c.p, c.a);
  ha_index s = ha_slot(h);
  // A slot whose key bits are larger holds another key that keeps it
  // (slots only grow): one plain load, no atomic.
  if (sh_key_bits(sh_load_slot(s)) <= sh_key_bits(c.r)) {
    sh_word old = sh_atomic_max_slot(s, c.r);
    // An emulated atomic that found its slot busy changed nothing: the same
    // probe again (HABUFFER_SH_PENDING), or the call is cut short (HABUFFER_SH_CUT), the carry
    // unchanged either way.
    uint missed = sh_atomic_missed();
    if (missed != 0u) return missed;
    c.iter += 1u;
    if (old == sh_word(0)) {
      sh_atomic_max_age(ha_cell(c.p), c.a);
      return HABUFFER_SH_STORED;
    }
    if (sh_key_bits(old) == sh_key_bits(c.r)) {
      // The same key: the larger record stays, the other is dropped. A live
      // record replacing the key's tombstone stores the key again.
      if (old < c.r && sh_live(old) == 0u) return HABUFFER_SH_REVIVED;
      return HABUFFER_SH_DUPLICATE;
    }
    if (old < c.r) {
      // Placed: carry the evicted record on from its own position and age.
      sh_atomic_max_age(ha_cell(c.p), c.a);
      uint old_age = sh_age(old);
      c.r = old;
      c.p = ha_owner(h, old_age);
      c.a = old_age;
    }
  } else {
    c.iter += 1u;
  }
  c.a += 1u;
  c.r = sh_with_age(c.r, c.a);
  return HABUFFER_SH_PENDING;
}

// Runs the call's steps until it ends; HABUFFER_SH_CUT when it was cut short (the
// loop ended by the driver's budget counts as cut: `c` holds where to resume).
uint sh_insert_run(HABUFFER_INOUT(ShCarry) c) {
  uint outcome = HABUFFER_SH_PENDING;
  while (outcome == HABUFFER_SH_PENDING) outcome = sh_insert_step(c);
  return outcome == HABUFFER_SH_PENDING ? HABUFFER_SH_CUT : outcome;
}
#endif

// The slot holding key k's record (live or tombstone), or -1 as all ones.
// Probes ages 1 .. M[cell] and stops at the first slot whose key bits are
// below k's at the age probed: had k gone on to a later age, it was refused
// here by a record of larger key bits, and a slot's key bits only grow
// (values change, erase keeps them): the paper's Proposition A (SPEC 7) with
// the quotient. An empty slot or a younger record is the common case; a
// record of the same age and a smaller quotient stops it too. The miss
// filter answers most absent keys before the max-age cell or any slot is
// read. Returns the slots read in `probes` (0 when the filter answered).
ha_index sh_find_slot(uvec2 k, HABUFFER_INOUT(uint) probes) {
  uvec2 p = sh_position(k);
  uint want = sh_key_quotient(k);
  probes = 0u;
  if (!sh_filter_may_hold(p, want)) return ~ha_index(0);
  uint amax = sh_load_max_age(ha_cell(p));
  for (uint a = 1u; a <= amax; a += 1u) {
    ha_index s = ha_slot(ha_probe(p, a));
    uint key = sh_key_bits(sh_load_slot(s));
    uint mine = (a << (31u - sh_age_bits)) | want;
    probes += 1u;
    if (key == mine) return s;
    if (key < mine) break;
  }
  return ~ha_index(0);
}
