/// @file
/// The blended technique's GLSL as text, embedded at build time by
/// techniques/blended/CMakeLists.txt: the file its CPU kernel shares and the GL
/// path's own environment. Declared extern here, as glsl_sources.h declares
/// the shared files, so the generated definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kBlendedGlsl;  ///< cpu/include/habuffer/techniques/blended/blended.glsl: wboit's and blend's formulas (shared with the CPU kernel)
extern const char* const kBlendedEnv;  ///< gl/glsl/blended_env.glsl: the blended baselines' outputs and accumulators
extern const char* const kBlendedEntry;  ///< gl/glsl/blended_entry.glsl: their insert call and composite

}  // namespace habuffer::gl
