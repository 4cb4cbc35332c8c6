#include "gl_context.h"

#include <memory>

#include "bindings.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer::python {
namespace {

std::recursive_mutex& context_mutex() {
  static std::recursive_mutex m;
  return m;
}

// Leaked on purpose: destroying an EGL context from a static destructor at
// interpreter exit races the driver's own teardown.
gl::EglContext*& context_slot() {
  static gl::EglContext* context = nullptr;
  return context;
}

}  // namespace

namespace {

// Uses on this thread inside one another (guarded by the mutex).
int& nesting() {
  static int n = 0;
  return n;
}

}  // namespace

GlContextUse::GlContextUse() : lock_(context_mutex()) {
  gl::EglContext*& c = context_slot();
  if (nesting() == 0) {
    if (!c)
      c = new gl::EglContext();  // current on this thread; GlError when none can be made (a later call tries again)
    else
      c->make_current();
  }
  ++nesting();
}

// The outermost use releases the context from its thread, so that a call
// from another Python thread can make it current (EGL refuses a context
// current on another thread).
GlContextUse::~GlContextUse() {
  if (--nesting() > 0) return;
  try {
    context_slot()->release_current();
  } catch (const gl::GlError&) {
    // The next use makes it current again, or raises EGL's reason then.
  }
}

void bind_gl_context(py::module_& m) {
  m.def(
      "gl_info",
      [] {
        gl::GlInfo info;
        {
          py::gil_scoped_release release;  // before the context's lock: never wait for it holding the GIL
          const GlContextUse use;
          info = gl::query_gl_info();
        }
        py::dict d;
        d["renderer"] = info.renderer;
        d["version"] = info.version;
        const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(info, Layout::L64);
        d["atomic_mode_64"] = mode ? gl::to_string(*mode) : std::string("none");
        return d;
      },
      "The OpenGL the GPU path would use (a headless EGL context, made on first use): renderer, version and the "
      "atomic mode of 64-bit records. Raises GlError where no context can be made.");
}

}  // namespace habuffer::python
