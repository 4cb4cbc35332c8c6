// What the opaque and the transparent passes share: flat shading of a mesh's
// constant colour, and the paper's depth t, linear eye depth between the near
// and far planes.
uniform vec3 r_colour;
uniform float r_opacity;
uniform float r_near;
uniform float r_far;
in vec3 v_eye;

// The face normal from screen-space derivatives, lit from the eye (either
// side of a face: transparent surfaces show both).
vec3 r_shaded_colour() {
  vec3 n = cross(dFdx(v_eye), dFdy(v_eye));
  float len = length(n);
  float facing = len > 0.0 ? abs(n.z) / len : 1.0;
  return r_colour * (0.35 + 0.65 * facing);
}

float r_depth() { return (-v_eye.z - r_near) / (r_far - r_near); }
