/// @file
/// The arrays technique's GLSL as text, embedded at build time by
/// techniques/arrays/CMakeLists.txt: the file its CPU kernel shares and the GL
/// path's own environment. Declared extern here, as glsl_sources.h declares
/// the shared files, so the generated definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kArraysGlsl;  ///< cpu/include/habuffer/techniques/arrays/arrays.glsl: fixed per-pixel arrays (shared with the CPU kernel)
extern const char* const kArraysEnv;  ///< gl/glsl/arrays_env.glsl: fixed arrays' environment

}  // namespace habuffer::gl
