// Writes every shader the library and the renderer compile, for every atomic
// mode (native64 too, which llvmpipe cannot run), as files a reference
// compiler reads: DIR/MODE-NAME.STAGE; and the installed host GLSL files
// (host_glsl_files) as a host includes them, after its own declarations.
// No GL context is needed.
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/host_glsl_files.h"
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
    // The gather counting nothing per pixel (every count's #if left out).
    shaders.push_back({"gather-plain", "frag", SceneRenderer::shader_sources(mode, {}, Technique::Ha, {}).gather_fragment});
    if (mode != gl::AtomicMode::Native32) {  // translucent shadows read 64-bit light records
      const SceneRenderer::Sources lit =
          SceneRenderer::shader_sources(mode, {}, Technique::Ha, {true, true}, ShadowReceiving{{}, true});
      shaders.push_back({"opaque-shadowed", "frag", lit.opaque_fragment});
      shaders.push_back({"gather-shadowed", "frag", lit.gather_fragment});
      shaders.push_back({"shadow-map", "frag", lit.shadow_map_fragment});
    }
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
  // The installed files after a host's declarations, with a host main.
  const std::vector<gl::GlslFile> files = gl::host_glsl_files();
  std::map<std::string, std::string> extensions;  // by mode
  std::map<std::string, std::string> texts;       // by path
  for (const gl::GlslFile& f : files) {
    texts[f.path] = f.text;
    if (f.path.ends_with("/extensions.glsl")) extensions[f.path.substr(0, f.path.find('/'))] = f.text;
  }
  for (const gl::GlslFile& f : files) {
    if (f.path.find('/') == std::string::npos) continue;  // spatial_lookup.glsl, for every mode: below
    const std::string name = f.path.substr(f.path.find('/') + 1);
    if (name == "extensions.glsl") continue;
    const std::string mode = f.path.substr(0, f.path.find('/'));
    const std::string& ext = extensions.at(mode);
    // The light lookup goes after a technique file of its mode: the HA-buffer's here.
    const bool light = name == "light_lookup.glsl";
    const bool fragment = light || name.find(".frag.") != std::string::npos;
    std::string source = "#version 450 core\n" + ext;
    source += fragment ? "layout(std140, binding = 0) uniform HostBlock { vec4 host_tint; };\nin vec4 host_colour;\n"
                       : "layout(local_size_x = 64) in;\nlayout(std430, binding = 0) buffer HostIn { vec4 host_in[]; };\n";
    if (light) source += texts.at(mode + "/ha.frag.glsl");
    source += f.text;
    source += light      ? "void main() { ha_insert_here(host_colour * habuffer_shadow_transmittance(host_colour.xyz)); }\n"
              : fragment ? "void main() { ha_insert_here(host_colour * host_tint); }\n"
                       : "void main() { uint i = gl_GlobalInvocationID.x;\n"
                         "  ha_insert(uvec2(i % 16u, i / 16u), host_in[i].w, ha_pack_rgba(vec4(host_in[i].rgb, 0.5))); }\n";
    const std::string base = name.substr(0, name.find('.'));
    const std::string path = dir + "/" + mode + "-host-" + base + "." + (fragment ? "frag" : "comp");
    std::ofstream out(path);
    out << source;
    if (!out) {
      std::fprintf(stderr, "habuffer_glsl_dump: cannot write %s\n", path.c_str());
      return 1;
    }
    ++written;
  }
  // The spatial hash's lookup (any mode) beside each mode's HA-buffer file, in a fragment shader.
  for (const auto& [mode, ext] : extensions) {
    const std::string path = dir + "/" + mode + "-host-spatial_lookup.frag";
    std::ofstream out(path);
    out << "#version 450 core\n" << ext << "in vec4 host_colour;\n" << texts.at(mode + "/ha.frag.glsl")
        << texts.at("spatial_lookup.glsl")
        << "void main() { uint v = 0u;\n"
           "  if (habuffer_spatial_find(uvec3(gl_FragCoord.xy, 0u), v)) ha_insert_here(unpackUnorm4x8(v));\n"
           "  if (habuffer_spatial_find_value(uvec3(gl_FragCoord.xy, 1u), v)) ha_insert_here(host_colour); }\n";
    if (!out) {
      std::fprintf(stderr, "habuffer_glsl_dump: cannot write %s\n", path.c_str());
      return 1;
    }
    ++written;
  }
  std::printf("%d shaders written to %s\n", written, dir.c_str());
  return 0;
}
