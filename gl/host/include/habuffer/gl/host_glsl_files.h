/// @file
/// The GLSL files a host's file-based shader pipeline includes (installed
/// under share/habuffer/glsl by the build's habuffer_write_glsl): each
/// technique's module, the light lookup and the spatial hash's lookup. The
/// host-export layer of the GL path: above the techniques and the effects it
/// writes files for.
#pragma once

#include <string>
#include <vector>

namespace habuffer::gl {

/// A file of the GLSL a host's file-based shader pipeline includes, as
/// installed under share/habuffer/glsl: `path` relative to that directory.
struct GlslFile {
  /// The path under share/habuffer/glsl and the file's text.
  std::string path, text;
};
/// Every such file: for each atomic mode, <mode>/extensions.glsl, and for each
/// technique with a GL path <mode>/<technique>.frag.glsl and .comp.glsl
/// (technique_module_body at the default, overridable bindings), for
/// native64 and emulated64 <mode>/light_lookup.glsl, and once for every mode
/// spatial_lookup.glsl (spatial_lookup_part), each with a comment header
/// saying how to use it. Needs no GL context.
std::vector<GlslFile> host_glsl_files();

}  // namespace habuffer::gl
