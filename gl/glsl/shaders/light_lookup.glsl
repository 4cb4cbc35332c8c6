// What a host shader calls for translucent shadows (after light_env.glsl
// and the hs_ instance of the shared sources).

// The light's transmittance for a receiver at light pixel `pixel` and light
// depth `depth` (t in [0, 1]): shared/ha_traverse.glsl's walk over the light
// buffer, with the block's bias. The CPU path's HaBuffer::transmittance
// gives the same value bit for bit.
float habuffer_shadow_transmittance(uvec2 pixel, float depth) {
  return hs_transmittance(pixel, hs_depth_code(depth), habuffer_light.bias);
}

// The same for world point p, mapped by the light's matrices with
// habuffer::LightView::sample's code (shared/ha_light_map.glsl); a point
// outside the light's frustum is lit: 1.
float habuffer_shadow_transmittance(vec3 p) {
  vec2 w = vec2(0.0);  // initialised: the map writes them through HABUFFER_INOUT (inout), which Mesa warns about
  float t = 0.0;
  if (!habuffer_light_map(habuffer_light.view, habuffer_light.projection, vec2(habuffer_light.map_size),
                          habuffer_light.near_plane, habuffer_light.far_plane, p, w, t))
    return 1.0;
  return habuffer_shadow_transmittance(uvec2(w), t);
}

// 2x2 percentage-closer filtering of the same: T at the four light pixels
// whose centres surround the point's window position (clamped to the map),
// weighted bilinearly (habuffer::transmittance_pcf does the same on the
// CPU). The receiver's own surface at the farthest of the four lies up to
// 1.4 pixels away, twice the nearest pixel's 0.7: the bias must double.
float habuffer_shadow_transmittance_pcf(vec3 p) {
  vec2 w = vec2(0.0);
  float t = 0.0;
  if (!habuffer_light_map(habuffer_light.view, habuffer_light.projection, vec2(habuffer_light.map_size),
                          habuffer_light.near_plane, habuffer_light.far_plane, p, w, t))
    return 1.0;
  uvec2 lo = uvec2(0u);
  uvec2 hi = uvec2(0u);
  vec2 f = vec2(0.0);
  hs_pcf_taps(w, habuffer_light.map_size, lo, hi, f);  // shared/ha_shadow_pcf.glsl
  return hs_pcf_blend(habuffer_shadow_transmittance(lo, t), habuffer_shadow_transmittance(uvec2(hi.x, lo.y), t),
                      habuffer_shadow_transmittance(uvec2(lo.x, hi.y), t), habuffer_shadow_transmittance(hi, t), f);
}
