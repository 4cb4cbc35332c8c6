// The one headless EGL context the module's GL calls share (the GPU build,
// scenes of the harness): made on first use, kept until the interpreter
// exits, made current on the calling thread for each use.
#pragma once

#include <mutex>

namespace habuffer::python {

/// Holds the module's context current on this thread for one call; made on
/// first use. Throws GlError (habuffer.GlError, the library's message) when
/// no context can be made. Uses are serialized: one GL call at a time.
/// Make it with the GIL released (and so destroy it before the GIL is taken
/// back): a thread waiting for the context's lock while holding the GIL
/// deadlocks with one that holds the lock and waits for the GIL.
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
