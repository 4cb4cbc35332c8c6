/// @file
/// The linked lists technique's GLSL as text, embedded at build time by
/// techniques/linked_lists/CMakeLists.txt: the file its CPU kernel shares and the GL
/// path's own environment. Declared extern here, as glsl_sources.h declares
/// the shared files, so the generated definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kListsGlsl;  ///< cpu/include/habuffer/techniques/linked_lists/lists.glsl: per-pixel linked lists (shared with the CPU kernel)
extern const char* const kSortedListsGlsl;  ///< cpu/include/habuffer/techniques/linked_lists/sorted_lists.glsl: lists kept sorted while inserting
extern const char* const kListsEnv;  ///< gl/glsl/lists_env.glsl: linked lists' environment
extern const char* const kSortedListsEnv;  ///< gl/glsl/sorted_lists_env.glsl: sorted lists' environment

}  // namespace habuffer::gl
