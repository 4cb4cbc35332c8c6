// Record packing of SPEC 2, written once for both paths.
// Host environment provides: type ha_word (uint or uint64_t), uint habuffer_age_bits,
// uint habuffer_coverage_bits (C: 0, or the samples S of a multisampled
// screen), uint ha_word_bits (32 or 64), uint ha_payload_bits (32 for L64, 0
// for L32), and ha_floor / ha_float_bits as the GLSL builtins floor / floatBitsToUint.
//
// The code field (32 - A bits) holds the depth code in its high 32 - A - C
// bits and, multisampled, the fragment's coverage mask (one bit per sample)
// in its low C bits (docs/spec-notes.md, "Multisampled records"): records
// order by depth, then coverage, then data, and with C = 0 the field is
// SPEC 2's depth code exactly.

uint ha_age_shift() { return ha_word_bits - habuffer_age_bits; }
// The code field's bits, 32 - A.
uint ha_code_bits() { return 32u - habuffer_age_bits; }
// The depth's own bits within it, D = 32 - A - C.
uint ha_depth_bits() { return ha_code_bits() - habuffer_coverage_bits; }
uint ha_max_age() { return (1u << habuffer_age_bits) - 1u; }
// The code field's largest value, 2^(32 - A) - 1.
uint ha_max_code() { return uint((ha_word(1) << ha_code_bits()) - ha_word(1)); }
// The coverage bits of a code field: (1 << C) - 1 (0 when not multisampled).
uint ha_coverage_mask() { return (1u << habuffer_coverage_bits) - 1u; }

ha_word ha_pack(uint age, uint code, uint data) {
  return (ha_word(age) << ha_age_shift()) | (ha_word(code) << ha_payload_bits) |
         ha_word(ha_payload_bits == 0u ? 0u : data);
}

uint ha_age(ha_word r) { return uint(r >> ha_age_shift()); }
// The record's high 32 bits (age and depth code; the whole record for L32).
// Records order as their high words do where those differ, and a 64-bit slot
// read while another invocation writes it may mix halves, but its high half
// is one value the slot held: the read-first checks compare these alone.
uint ha_high(ha_word r) { return uint(r >> (ha_word_bits - 32u)); }

uint ha_code(ha_word r) {
  return uint((r >> ha_payload_bits) & ha_word(ha_max_code()));
}

// The payload of an L64 record; L32 records have none.
uint ha_data(ha_word r) { return ha_payload_bits == 0u ? 0u : uint(r & ha_word(0xFFFFFFFFu)); }

ha_word ha_with_age(ha_word r, uint age) {
  ha_word low = (ha_word(1) << ha_age_shift()) - ha_word(1);
  return (r & low) | (ha_word(age) << ha_age_shift());
}

// Opacity of an L64 colour record (alpha in the low byte), as a float in [0,1].
float ha_alpha(ha_word r) { return float(ha_data(r) & 255u) * (1.0f / 255.0f); }

// Depth validity by bit pattern rather than isnan(): shader compilers may
// assume NaN never happens, but integer compares are always honoured.
bool ha_depth_valid(float t) {
  uint bits = ha_float_bits(t);
  return bits <= HABUFFER_FLOAT_ONE_BITS || bits == HABUFFER_FLOAT_NEG_ZERO_BITS;
}

// code(t) = (2^D - 1) - min(2^D - 1, floor(t * 2^D)), in the code field's
// high D bits (shifted left by C); t * 2^D is exact in float32 (a
// power-of-two scale), so both paths get the same integer.
uint ha_depth_code(float t) {
  uint top = (1u << ha_depth_bits()) - 1u;
  float scaled = ha_floor(t * float(1u << ha_depth_bits()));
  uint q = uint(scaled);
  return (top - (q > top ? top : q)) << habuffer_coverage_bits;
}

// The samples a fragment's coverage word gives, as the code field's low C
// bits: 0 (no mask given) is the whole pixel; bits beyond the S samples are
// ignored. Not multisampled (C = 0): always 0.
uint ha_fragment_coverage(uint coverage) {
  return coverage == 0u ? ha_coverage_mask() : coverage & ha_coverage_mask();
}

// Whether a fragment's coverage word covers a sample of the screen: always
// when not multisampled; else its mask must name one of the S samples.
bool ha_covers_sample(uint coverage) { return habuffer_coverage_bits == 0u || ha_fragment_coverage(coverage) != 0u; }

// Whether a fragment makes a record: a valid depth (SPEC 2) and, when
// multisampled, a sample of the screen in its mask; else it is invalid.
bool ha_fragment_valid(float t, uint coverage) { return ha_depth_valid(t) && ha_covers_sample(coverage); }

// The code field of a fragment at depth t with coverage word `coverage`.
uint ha_fragment_code(float t, uint coverage) { return ha_depth_code(t) | ha_fragment_coverage(coverage); }
