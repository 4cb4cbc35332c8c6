// The one headless EGL context the module's GL calls share (the GPU build,
// scenes of the harness): made on first use, kept until the interpreter
// exits, made current on the calling thread for each use.
#pragma once

#include <mutex>

namespace habuffer::python {

/// Holds the module's context current on this thread for one call; made on
/// first use. Raises habuffer.GlError (the library's message) when no
/// context can be made. Uses are serialized: one GL call at a time.
class GlContextUse {
 public:
  GlContextUse();
  ~GlContextUse();
  GlContextUse(const GlContextUse&) = delete;
  GlContextUse& operator=(const GlContextUse&) = delete;

 private:
  std::unique_lock<std::recursive_mutex> lock_;
};

}  // namespace habuffer::python
