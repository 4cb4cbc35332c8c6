/// @file
/// The kbuffer technique's GLSL as text, embedded at build time by
/// techniques/kbuffer/CMakeLists.txt: the file its CPU kernel shares and the GL
/// path's own environment. Declared extern here, as glsl_sources.h declares
/// the shared files, so the generated definitions have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kKBufferGlsl;  ///< cpu/include/habuffer/techniques/kbuffer/kbuffer.glsl: the k-buffer (shared with the CPU kernel)
extern const char* const kKBufferEnv;  ///< gl/glsl/kbuffer_env.glsl: the k-buffer's environment
extern const char* const kKBufferEntry;  ///< gl/glsl/kbuffer_entry.glsl: the k-buffer's insert call
extern const char* const kKBufferCountCompute;  ///< gl/glsl/kb_count.comp.glsl: the k-buffer's count pass

}  // namespace habuffer::gl
