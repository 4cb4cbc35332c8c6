// Translucent shadows' per-record step (habuffer/transmittance.h), written
// once for both paths: the HA-buffer's walk (ha_traverse.glsl's
// ha_transmittance, on the CPU and the GPU) and the walk over any
// technique's lists (core/effects/src/transmittance.cpp) call these, so every path
// multiplies the same float32 factors in the same order.

// The code a light record must exceed to lie in front of a receiver at
// `code` by more than `bias` codes: code + bias, clamped to `cap` (the
// largest code a record can have) so it never wraps.
uint ha_shadow_front(uint code, uint bias, uint cap) { return code + min(bias, cap - code); }

// T after one more record in front, whose data word carries the 8-bit
// opacity in its low byte (as ha_alpha reads it). precise: no fused
// multiply-add, so every GPU gives the C++ path's product.
float ha_shadow_through(float t, uint data) {
  HABUFFER_PRECISE float keep = 1.0f - float(data & 255u) * (1.0f / 255.0f);
  HABUFFER_PRECISE float next = t * keep;
  return next;
}
