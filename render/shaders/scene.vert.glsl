#version 450 core
// Scene geometry, in eye space for the flat shading and the linear depth t.
layout(location = 0) in vec3 r_position;
uniform mat4 r_view;
uniform mat4 r_projection;
out vec3 v_eye;

void main() {
  vec4 eye = r_view * vec4(r_position, 1.0);
  v_eye = eye.xyz;
  gl_Position = r_projection * eye;
}
