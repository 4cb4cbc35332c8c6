// Front-to-back compositing of SPEC 7, shared by every technique (the same
// float32 operations in the same order, so exact techniques give identical
// images), written once for both paths.

vec4 ha_unpack_rgba(uint data) {
  return vec4(float(data >> 24u), float((data >> 16u) & 255u), float((data >> 8u) & 255u),
              float(data & 255u)) * (1.0f / 255.0f);
}

// Straight-alpha front-to-back "under" operator, float32.
// HABUFFER_PRECISE (GLSL's precise) keeps every multiply and add apart, as
// the C++ side computes them.
vec4 ha_blend_under(vec4 c, vec4 f) {
  HABUFFER_PRECISE float w = (1.0f - c.a) * f.a;
  HABUFFER_PRECISE vec3 rgb = vec3(c) + w * vec3(f);
  HABUFFER_PRECISE float a = c.a + w;
  return vec4(rgb, a);
}

vec4 ha_finish(vec4 c, vec3 background) {
  HABUFFER_PRECISE vec3 rgb = vec3(c) + (1.0f - c.a) * background;
  return vec4(rgb, c.a);
}

// A multisampled pixel's resolve (issue 37; docs/spec-notes.md,
// "Multisampled records"): the pixel's records are walked once, nearest
// first, each blended under the accumulator of every sample its coverage
// mask names, and the pixel is the mean of its S samples, each finished
// over the background, summed in sample order and scaled by 1/S (a power of
// two: exact), the same float32 operations on both paths. A record of the
// depth code and data a sample blended last is that sample's duplicate
// (two fragments of one surface whose masks overlap, which a pixel of one
// sample merges by SPEC 6): it is not blended into that sample again.
// (Declared once per GLSL module, which may hold a second, renamed instance
// of this file, the light lookup's; once per kernel class in C++.)
#if defined(__cplusplus) || !defined(HABUFFER_SAMPLE_COLOURS_DECLARED)
#ifndef __cplusplus
#define HABUFFER_SAMPLE_COLOURS_DECLARED
#endif
struct HaSampleColours {
  vec4 c[HABUFFER_MAX_SAMPLES];
  uint last_depth[HABUFFER_MAX_SAMPLES];  // the depth code (coverage bits 0) a sample blended last
  uint last_data[HABUFFER_MAX_SAMPLES];   // and its data
};
#endif

HaSampleColours ha_samples_begin() {
  HaSampleColours s;
  for (uint i = 0u; i < HABUFFER_MAX_SAMPLES; ++i) {
    s.c[i] = vec4(0.0f);
    s.last_depth[i] = 0xFFFFFFFFu;  // no depth code: codes have at most 32 - A <= 28 bits
    s.last_data[i] = 0u;
  }
  return s;
}

// Blends a record of depth code `depth` (coverage bits 0) and data `data`
// under the first `samples` accumulators whose bit is set in `mask`, but
// for a sample whose last record had the same depth code and data.
void ha_samples_under(HABUFFER_INOUT(HaSampleColours) s, uint samples, uint mask, uint depth, uint data) {
  for (uint i = 0u; i < samples; ++i) {
    if (((mask >> i) & 1u) == 0u || (s.last_depth[i] == depth && s.last_data[i] == data)) continue;
    s.last_depth[i] = depth;
    s.last_data[i] = data;
    s.c[i] = ha_blend_under(s.c[i], ha_unpack_rgba(data));
  }
}

vec4 ha_samples_finish(HaSampleColours s, uint samples, vec3 background) {
  HABUFFER_PRECISE vec4 sum = vec4(0.0f);
  for (uint i = 0u; i < samples; ++i) sum = sum + ha_finish(s.c[i], background);
  return sum * (1.0f / float(samples));
}

// A technique's composite walk blends a pixel's records, nearest first, into
// one HABUFFER_PIXEL_COLOUR (ha_pixel_begin, ha_pixel_under of each record's
// code field and data, ha_pixel_finish), whose kind the module's resolve
// mode fixes, so each technique writes its walk once for every mode:
// - one sample per pixel (every CPU kernel; a GL module of one sample): a
//   vec4, every record blended (SPEC 7's composite, unchanged);
// - HABUFFER_RESOLVE_PIXEL (a GL module of S samples): the per-pixel
//   resolve, ha_samples_* above; the CPU path runs the same functions over
//   each pixel's list (FragmentBuffer::composite_image), so both agree bit for bit;
// - HABUFFER_RESOLVE_SAMPLE (the per-sample resolve, drawn into a
//   multisampled target with sample shading): the one sample
//   habuffer_resolve_sample() of the invocation, its records alone, by the
//   same ha_samples_* (as sample 0 of one).
// The multisampled modes need ha_record.glsl (the coverage mask of a code).
#ifndef HABUFFER_PIXEL_COLOUR
#if defined(HABUFFER_RESOLVE_PIXEL) || defined(HABUFFER_RESOLVE_SAMPLE)
#define HABUFFER_PIXEL_COLOUR HaSampleColours
#else
#define HABUFFER_PIXEL_COLOUR vec4
#endif
#endif

HABUFFER_PIXEL_COLOUR ha_pixel_begin() {
#if defined(HABUFFER_RESOLVE_PIXEL) || defined(HABUFFER_RESOLVE_SAMPLE)
  return ha_samples_begin();
#else
  return vec4(0.0f);
#endif
}

void ha_pixel_under(HABUFFER_INOUT(HABUFFER_PIXEL_COLOUR) c, uint code, uint data) {
#if defined(HABUFFER_RESOLVE_PIXEL)
  ha_samples_under(c, habuffer_coverage_bits, code & ha_coverage_mask(), code & ~ha_coverage_mask(), data);
#elif defined(HABUFFER_RESOLVE_SAMPLE)
  ha_samples_under(c, 1u, (code >> habuffer_resolve_sample()) & 1u, code & ~ha_coverage_mask(), data);
#else
  HABUFFER_UNUSED(code);
  c = ha_blend_under(c, ha_unpack_rgba(data));
#endif
}

vec4 ha_pixel_finish(HABUFFER_PIXEL_COLOUR c, vec3 background) {
#if defined(HABUFFER_RESOLVE_PIXEL)
  return ha_samples_finish(c, habuffer_coverage_bits, background);
#elif defined(HABUFFER_RESOLVE_SAMPLE)
  return ha_finish(c.c[0], background);
#else
  return ha_finish(c, background);
#endif
}
