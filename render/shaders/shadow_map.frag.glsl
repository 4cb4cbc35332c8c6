// The transmittance map: the light's T at each pixel's nearest surface
// (opaque or transparent, depth-tested), one lookup per covered pixel: the
// --heatmap shadow image and the stats' lookup time.
layout(location = 0) out float r_out_transmittance;

void main() {
#ifdef R_SHADOWS_PCF
  r_out_transmittance = habuffer_shadow_transmittance_pcf(v_world);
#else
  r_out_transmittance = habuffer_shadow_transmittance(v_world);
#endif
}
