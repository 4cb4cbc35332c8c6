/// @file
/// The HA-buffer's own GL GLSL as text, embedded at build time by
/// techniques/ha/CMakeLists.txt: its environment, its insert entry (the
/// k-buffer's module reuses it) and its clear pass. Declared extern here, as
/// glsl_sources.h declares the shared files, so the generated definitions
/// have external linkage.
#pragma once

namespace habuffer::gl {

extern const char* const kHaEnv;              ///< techniques/ha/gl/glsl/ha_env.glsl: the HA-buffer's environment
extern const char* const kHaEntry;            ///< techniques/ha/gl/glsl/ha_entry.glsl: its insert call and composite
extern const char* const kClearPassFragment;  ///< techniques/ha/gl/glsl/clear_pass.frag.glsl: the clear pass

}  // namespace habuffer::gl
