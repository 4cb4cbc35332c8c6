/// @file
/// Paged lists' GLSL, embedded by gl/CMakeLists.txt (paged_lists_glsl.cpp):
/// declared extern here, as glsl_sources.h declares the shared files, so the
/// generated `const char* const` definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kHaPagedLists;   ///< core/include/habuffer/techniques/paged_lists/ha_paged_lists.glsl
extern const char* const kPagedListsEnv;  ///< gl/include/habuffer/gl/techniques/paged_lists/paged_lists_env.glsl

}  // namespace habuffer::gl
