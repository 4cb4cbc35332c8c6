// Opaque pass: ordinary depth-tested rendering of the opaque meshes into a
// colour image (the transparent layers' background) and their t.
layout(location = 0) out vec4 r_out_colour;
layout(location = 1) out float r_out_depth;

void main() {
  r_out_colour = vec4(r_shaded_colour(), 1.0);
  r_out_depth = r_depth();
}
