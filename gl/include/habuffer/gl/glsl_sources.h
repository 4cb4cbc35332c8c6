// The shared algorithm as GLSL text (generated from core/shared/ at build
// time) and the assembly of complete shaders from it.
#pragma once

#include <string>

#include "habuffer/gl/gl_info.h"

namespace habuffer::gl {

extern const char* const kHaConstants;
extern const char* const kHaRecord;
extern const char* const kHaProbe;
extern const char* const kHaInsert;
extern const char* const kHaTraverse;
extern const char* const kPreludeCommon;
extern const char* const kPreludeNative32;
extern const char* const kPreludeEmulated64;
extern const char* const kInsertStreamCompute;

// #version line, the atomic mode's prelude, the common prelude, then constants, record, probe,
// insert and traversal: the module a host shader (or our entries) appends to.
std::string ha_module(AtomicMode mode);

// The compute shader that inserts a fragment stream held in a buffer.
std::string insert_stream_compute(AtomicMode mode);

}  // namespace habuffer::gl
