// Writes every shader the library and the renderer compile, for every atomic
// mode (native64 too, which llvmpipe cannot run), as files a reference
// compiler reads: DIR/MODE-NAME.STAGE. No GL context is needed.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "habuffer/gl/glsl_sources.h"
#include "habuffer/render/scene_renderer.h"

int main(int argc, char** argv) {
  using namespace habuffer;
  if (argc != 2) {
    std::fprintf(stderr, "usage: habuffer_glsl_dump DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  int written = 0;
  for (gl::AtomicMode mode : {gl::AtomicMode::Native32, gl::AtomicMode::Native64, gl::AtomicMode::Emulated64}) {
    std::vector<gl::ShaderSource> shaders = gl::library_shaders(mode);
    const SceneRenderer::Sources r = SceneRenderer::shader_sources(mode, {});
    shaders.push_back({"scene", "vert", r.vertex});
    shaders.push_back({"opaque", "frag", r.opaque_fragment});
    shaders.push_back({"gather", "frag", r.gather_fragment});
    for (const gl::ShaderSource& s : shaders) {
      const std::string path = dir + "/" + gl::to_string(mode) + "-" + s.name + "." + s.stage;
      std::ofstream out(path);
      out << s.source;
      if (!out) {
        std::fprintf(stderr, "habuffer_glsl_dump: cannot write %s\n", path.c_str());
        return 1;
      }
      ++written;
    }
  }
  std::printf("%d shaders written to %s\n", written, dir.c_str());
  return 0;
}
