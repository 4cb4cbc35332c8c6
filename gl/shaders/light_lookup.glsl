// What a host shader calls for translucent shadows (after light_env.glsl
// and the hs_ instance of the shared sources).

// The light's transmittance for a receiver at light pixel `pixel` and light
// depth `depth` (t in [0, 1]): shared/ha_traverse.glsl's walk over the light
// buffer, with the block's bias. The CPU path's HaBuffer::transmittance
// gives the same value bit for bit.
float habuffer_shadow_transmittance(uvec2 pixel, float depth) {
  return hs_transmittance(pixel, hs_depth_code(depth), habuffer_light.bias);
}

// The same for world point p, mapped by the light's matrices as
// habuffer::LightView::sample maps it (a point outside the light's frustum
// is lit: 1). The mapping's float operations may round differently on a
// GPU at a light pixel's edge or a depth code's; the lookup itself does not.
float habuffer_shadow_transmittance(vec3 p) {
  vec4 eye = habuffer_light.view * vec4(p, 1.0);
  vec4 clip = habuffer_light.projection * eye;
  if (!(clip.w > 0.0)) return 1.0;
  vec2 w = (clip.xy / clip.w * 0.5 + 0.5) * vec2(habuffer_light.map_size);
  float t = (-eye.z - habuffer_light.near_plane) / (habuffer_light.far_plane - habuffer_light.near_plane);
  if (any(lessThan(w, vec2(0.0))) || any(greaterThanEqual(w, vec2(habuffer_light.map_size))) || !(t >= 0.0 && t <= 1.0))
    return 1.0;
  return habuffer_shadow_transmittance(uvec2(w), t);
}
