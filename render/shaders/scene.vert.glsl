#version 450 core
// Scene geometry, in eye space for the flat shading and the linear depth t,
// and in world space for translucent shadows' light lookup (R_SHADOWS).
layout(location = 0) in vec3 r_position;
uniform mat4 r_view;
uniform mat4 r_projection;
out vec3 v_eye;
out vec3 v_world;

void main() {
  vec4 eye = r_view * vec4(r_position, 1.0);
  v_eye = eye.xyz;
  v_world = r_position;  // the meshes are in world space
  gl_Position = r_projection * eye;
}
