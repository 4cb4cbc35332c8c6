// Saturation depth (guacamole, Fig. 6), written once for both paths, for the
// techniques with early cull: a fragment culled because its pixel is
// saturated raises the pixel's saturation code to its own (atomic max of
// depth codes: larger is nearer), and a later fragment strictly behind it
// (a smaller code) is hidden by the same opacity, so it is rejected before
// insertion (HABUFFER_SATURATED). A code equal to the saturation code may still
// sort in front of the culled record (by its data), so it is inserted.
//
// Host environment provides: uint habuffer_saturation (0: off), uvec2
// habuffer_screen_size, uint ha_load_saturation(uint pixel) (may be stale: codes
// only grow during a gather, so a stale one rejects less, never wrongly) and
// void ha_max_saturation(uint pixel, uint code) (atomic max).

uint ha_saturation_pixel(uvec2 p) { return p.x + p.y * habuffer_screen_size.x; }

bool ha_saturated(uvec2 p, uint code) {
  return habuffer_saturation != 0u && code < ha_load_saturation(ha_saturation_pixel(p));
}

void ha_saturate(uvec2 p, uint code) {
  if (habuffer_saturation == 0u) return;
  uint pixel = ha_saturation_pixel(p);
  if (ha_load_saturation(pixel) < code) ha_max_saturation(pixel, code);
}
