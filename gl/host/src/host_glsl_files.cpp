#include "habuffer/gl/host_glsl_files.h"

#include <string>
#include <vector>

#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_spatial_hash.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/gl/technique_registry.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::gl {

namespace {

// The binding names a file of technique group `group` reads: its own
// buffers', the shared ones and PARAMS, as "HABUFFER_BINDING_TABLE MAX_AGE ...".
std::string binding_names(unsigned group) {
  std::string own, shared;
  for (const GlBindings::Point& p : GlBindings::points()) {
    if (p.group != 0 && p.group != group) continue;
    std::string& list = p.group == 0 ? shared : own;
    const std::string name = GlBindings::macro_name(p.name).substr(std::string("HABUFFER_BINDING_").size());
    list += (list.empty() ? "" : " ") + name;
  }
  return "HABUFFER_BINDING_" + own + " " + shared + " PARAMS";
}

// The light lookup for file-based pipelines (gl/shadow_lookup.h): its
// binding points overridable, after a technique file of the same mode.
std::string light_lookup_file(AtomicMode mode) {
  return "// habuffer " HABUFFER_VERSION ": translucent shadows' light lookup, atomic mode " + to_string(mode) +
         ".\n"
         "// Place after a technique file of the same mode (it needs its constants), then call\n"
         "//   float habuffer_shadow_transmittance(vec3 world_point)\n"
         "//   float habuffer_shadow_transmittance(uvec2 light_pixel, float light_depth)\n"
         "// with the light buffer bound as habuffer::gl::GlShadowLookup binds it (or the block HabufferLight\n"
         "// written by the host with its own light matrices). Binding points: #define any of\n"
         "//   HABUFFER_LIGHT_BINDING_TABLE MAX_AGE OFFSETS (shader-storage) PARAMS (uniform)\n"
         "// before this file to move them, with the same numbers as habuffer::gl::GlLightBindings.\n" +
         light_lookup_part(GlLightBindings{}, mode, true);
}

// The spatial hash's lookup for file-based pipelines (gl_spatial_hash.h):
// one file for every mode (it reads slots as uvec2), points overridable.
std::string spatial_lookup_file() {
  return "// habuffer " HABUFFER_VERSION ": the spatial hash's lookup (habuffer::gl::GlSpatialHash), for any shader\n"
         "// stage and any atomic mode (no 64-bit integers needed). Place after `#version 450 core`, at global\n"
         "// scope (beside a technique file or without one), then call\n"
         "//   bool habuffer_spatial_find(uvec3 key, out uint stored)       // the rule's encoding, as GlSpatialHash::find\n"
         "//   bool habuffer_spatial_find_value(uvec3 key, out uint value)  // decoded, as SpatialHash::find\n"
         "// with the table bound by GlSpatialHash::bind_for_lookup(). Binding points: #define any of\n"
         "//   HABUFFER_SPATIAL_BINDING_TABLE MAX_AGE OFFSETS (shader-storage) PARAMS (uniform)\n"
         "// before this file to move them, with the same numbers as habuffer::gl::GlSpatialBindings.\n"
         "// Reserved names: sh_*, habuffer_spatial*, HabufferSpatial*, HABUFFER_SPATIAL_*, HABUFFER_SH_*.\n" +
         spatial_lookup_part(GlSpatialBindings{}, true);
}

}  // namespace

std::vector<GlslFile> host_glsl_files() {
  const GlBindings defaults;
  std::vector<GlslFile> files;
  for (AtomicMode mode : {AtomicMode::Native32, AtomicMode::Native64, AtomicMode::Emulated64}) {
    const std::string dir = to_string(mode) + "/";
    const std::string layout = mode == AtomicMode::Native32 ? "L32" : "L64";
    files.push_back({dir + "extensions.glsl",
                     "// habuffer " HABUFFER_VERSION ": the #extension lines of atomic mode " + to_string(mode) +
                         ", right after the shader's #version 450 line and before any code.\n" +
                         module_extensions(mode)});
    for (Technique t : all_techniques())
      for (ShaderStage stage : {ShaderStage::Fragment, ShaderStage::Compute}) {
        const bool fragment = stage == ShaderStage::Fragment;
        if (!fragment && !stores_lists(t)) continue;  // the blended baselines need the blender: fragment shaders only
        std::string head = "// habuffer " HABUFFER_VERSION ": technique " + to_string(t) + ", atomic mode " +
                           to_string(mode) + " (" + layout + " records), for " +
                           (fragment ? "fragment" : "compute") + " shaders.\n";
        head +=
            "// Place after `#version 450 core` and the lines of extensions.glsl, anywhere at global scope\n"
            "// (after the host's own declarations too), then call\n"
            "//   uint habuffer_insert(uvec2 pixel, float depth, uint rgba)  // rgba: packUnorm4x8, straight alpha\n"
            "// once per fragment. Binding points (defaults: this technique's own buffers from 16, the shared\n"
            "// ones 19..24, uniform 16): #define any of\n"
            "//   " + binding_names(gl_descriptor(t).binding_group) + "\n"
            "// before this file to move them, with the same numbers as the host's habuffer::gl::GlBindings\n"
            "// (GlBindings::glsl_defines() writes them). Another technique's names do not move this one's\n"
            "// buffers: defining only those is an #error.\n"
            "// Reserved names: ha_*, Ha*, habuffer_*, HABUFFER_*, ll_*, fa_*, sl_*, kb_*, bl_*, wb_*.\n";
        if (!stores_lists(t))
          head +=
              "// This technique blends: it declares `out vec4 ha_blended_accum` at location 0 (wboit also\n"
              "// ha_blended_revealage at 1; declare no outputs of your own there). Call habuffer_insert at most once\n"
              "// per invocation with the invocation's own pixel (habuffer_insert_here), discard where you call none,\n"
              "// and draw into the technique's gather_framebuffer() (the frame driver binds it and the blend\n"
              "// setup around your gather).\n";
        files.push_back({dir + to_string(t) + (fragment ? ".frag.glsl" : ".comp.glsl"),
                         head + technique_module_body(t, mode, defaults, stage, true)});
      }
    if (mode != AtomicMode::Native32) files.push_back({dir + "light_lookup.glsl", light_lookup_file(mode)});
  }
  files.push_back({"spatial_lookup.glsl", spatial_lookup_file()});
  return files;
}

}  // namespace habuffer::gl
