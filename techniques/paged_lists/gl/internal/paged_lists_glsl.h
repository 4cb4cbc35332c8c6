/// @file
/// The paged lists technique's GLSL as text, embedded at build time by
/// techniques/paged_lists/CMakeLists.txt: the file its CPU kernel shares and the GL
/// path's own environment. Declared extern here, as glsl_sources.h declares
/// the shared files, so the generated definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kPagedListsGlsl;  ///< cpu/include/habuffer/techniques/paged_lists/paged_lists.glsl: paged lists (shared with the CPU kernel)
extern const char* const kPagedListsEnv;  ///< gl/glsl/paged_lists_env.glsl: paged lists' environment

}  // namespace habuffer::gl
