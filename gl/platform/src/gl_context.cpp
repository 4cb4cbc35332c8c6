#include "habuffer/gl/gl_context.h"

#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <string>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {
namespace {

using GetCurrentContext = void* (*)();

// glXGetCurrentContext of a GLX library the process has already loaded
// (a windowed host: GLFW, SDL), else nullptr. Never loads one itself.
GetCurrentContext glx_current_context() {
  static const GetCurrentContext f = [] {
    for (const char* lib : {"libGLX.so.0", "libGL.so.1"}) {
      if (void* h = dlopen(lib, RTLD_LAZY | RTLD_NOLOAD)) {
        void* sym = dlsym(h, "glXGetCurrentContext");
        dlclose(h);  // RTLD_NOLOAD took a reference to a library that stays loaded
        if (sym != nullptr) return reinterpret_cast<GetCurrentContext>(sym);
      }
    }
    return GetCurrentContext{nullptr};
  }();
  return f;
}

std::string version_text() {
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return v != nullptr ? v : "unknown";
}

}  // namespace

const void* current_context() {
  if (EGLContext c = eglGetCurrentContext(); c != EGL_NO_CONTEXT) return c;
  if (const GetCurrentContext glx = glx_current_context()) return glx();
  return nullptr;
}

void require_context(const char* call) {
  if (current_context() == nullptr)
    throw GlError(std::string(call) + ": no OpenGL context is current on this thread (make the host's context current first)");
  const int version = epoxy_gl_version();
  if (version < 45 || epoxy_is_desktop_gl() == 0)
    throw GlError(std::string(call) + ": OpenGL 4.5 core is needed, the current context is " + version_text());
}

ContextBound::ContextBound(const char* what) {
  require_context(what);
  context_ = current_context();
}

void ContextBound::check(const char* call) const {
  const void* now = current_context();
  if (now == context_) return;
  if (now == nullptr)
    throw GlError(std::string(call) + ": no OpenGL context is current on this thread (this object's was made current elsewhere or released)");
  throw GlError(std::string(call) +
                ": the current OpenGL context is not the one this object was made on (make that context current; "
                "a sharing context does not share the library's vertex arrays and framebuffers)");
}

bool ContextBound::current() const { return current_context() == context_; }

}  // namespace habuffer::gl
