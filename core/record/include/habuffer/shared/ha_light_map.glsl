// A world point in a light's view (translucent shadows, habuffer/light_view.h),
// written once for both paths: its window position (pixels) and its depth
// t, linear in the light's eye depth between `near_plane` and `far_plane`
// as habuffer::Camera maps the view's. False outside the frustum (beside
// the map, before the near plane or beyond the far one). The GPU may fuse
// the matrix products' multiply-adds: at a light pixel's edge or a depth
// code's the GPU's sample may round to the neighbour.
bool habuffer_light_map(mat4 view, mat4 projection, vec2 size, float near_plane, float far_plane, vec3 p,
                        HABUFFER_INOUT(vec2) window, HABUFFER_INOUT(float) depth) {
  vec4 eye = view * vec4(p, 1.0f);
  vec4 clip = projection * eye;
  if (!(clip.w > 0.0f)) return false;
  window = vec2(clip.x / clip.w * 0.5f + 0.5f, clip.y / clip.w * 0.5f + 0.5f) * size;
  depth = (-eye.z - near_plane) / (far_plane - near_plane);
  return window.x >= 0.0f && window.y >= 0.0f && window.x < size.x && window.y < size.y && depth >= 0.0f &&
         depth <= 1.0f;
}
