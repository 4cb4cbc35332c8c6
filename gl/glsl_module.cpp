#include <string>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

std::string ha_module(AtomicMode mode) {
  if (mode == AtomicMode::Native64) throw GlError("atomic mode native64 is not implemented yet");
  const char* prelude = mode == AtomicMode::Native32 ? kPreludeNative32 : kPreludeEmulated64;
  std::string s = "#version 450 core\n";
  for (const char* part : {prelude, kPreludeCommon, kHaConstants, kHaRecord, kHaProbe, kHaInsert, kHaTraverse}) {
    s += part;
    s += '\n';
  }
  return s;
}

std::string insert_stream_compute(AtomicMode mode) { return ha_module(mode) + kInsertStreamCompute; }

}  // namespace habuffer::gl
