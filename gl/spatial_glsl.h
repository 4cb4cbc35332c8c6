// The spatial hash's GLSL as text, embedded at build time (gl/CMakeLists.txt):
// the shared sources of core/include/habuffer/spatial/ and its GL shaders.
#pragma once

namespace habuffer::gl {

extern const char* const kShConstants;      ///< spatial/sh_constants.h: outcomes and limits, shared with C++
extern const char* const kShSpatial;        ///< spatial/sh_spatial.glsl: record, probe, insert step, lookup
extern const char* const kShEnv;            ///< gl/shaders/spatial_env.glsl: the GPU's environment for it
extern const char* const kShInsertCompute;  ///< gl/shaders/spatial_insert.comp.glsl: the insert pass
extern const char* const kShFindCompute;    ///< gl/shaders/spatial_find.comp.glsl: the lookup pass

}  // namespace habuffer::gl
