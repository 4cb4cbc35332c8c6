// The spatial hash's GLSL as text, embedded at build time (gl/effects/CMakeLists.txt):
// the shared sources of core/spatial/include/habuffer/spatial/ and its GL shaders.
#pragma once

namespace habuffer::gl {

extern const char* const kShConstants;       ///< spatial/sh_constants.h: outcomes and limits, shared with C++
extern const char* const kShSpatial;         ///< spatial/sh_spatial.glsl: record, probe, insert step, lookup
extern const char* const kShBlock;           ///< gl/effects/shaders/spatial_block.glsl: the parameter block HabufferSpatial
extern const char* const kShEnv;             ///< gl/effects/shaders/spatial_env.glsl: the compute passes' environment for it
extern const char* const kShKeys;            ///< gl/effects/shaders/spatial_keys.glsl: domain check, fold, one key's lookup
extern const char* const kShRecordsCompute;  ///< gl/effects/shaders/spatial_records.comp.glsl: keys to insert records
extern const char* const kShInsertCompute;   ///< gl/effects/shaders/spatial_insert.comp.glsl: the insert pass
extern const char* const kShFindCompute;     ///< gl/effects/shaders/spatial_find.comp.glsl: the lookup pass
extern const char* const kShLookupEnv;       ///< gl/effects/shaders/spatial_lookup_env.glsl: a host shader's environment
extern const char* const kShLookup;          ///< gl/effects/shaders/spatial_lookup.glsl: habuffer_spatial_find

}  // namespace habuffer::gl
