#include <string>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

std::string ha_module(AtomicMode mode) {
  if (mode != AtomicMode::Native32)
    throw GlError("atomic mode " + to_string(mode) + " is not implemented yet (only native32)");
  std::string s = "#version 450 core\n";
  for (const char* part : {kPreludeNative32, kHaConstants, kHaRecord, kHaProbe, kHaInsert, kHaTraverse}) {
    s += part;
    s += '\n';
  }
  return s;
}

std::string insert_stream_compute(AtomicMode mode) { return ha_module(mode) + kInsertStreamCompute; }

}  // namespace habuffer::gl
