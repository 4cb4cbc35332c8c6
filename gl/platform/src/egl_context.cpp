#include "habuffer/gl/egl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {
namespace {

std::string egl_error(const char* what) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", what, eglGetError());
  return buf;
}

std::optional<int> device_from_env() {
  const char* v = std::getenv("HABUFFER_EGL_DEVICE");
  if (v == nullptr || *v == '\0') return std::nullopt;
  char* end = nullptr;
  const long i = std::strtol(v, &end, 10);
  if (*end != '\0' || i < 0) throw GlError(std::string("HABUFFER_EGL_DEVICE='") + v + "' is not a device index");
  return static_cast<int>(i);
}

// The displays the library initialised itself, with the EglContexts alive
// on each: a display is terminated when the last of them goes, and only if
// the library initialised it (a display the host had initialised, or the
// same device display a host shares, is the host's: eglTerminate would
// break its contexts, EGL_BAD_DISPLAY... 0x3008 at its next eglMakeCurrent).
struct DisplayUsers {
  std::mutex mutex;
  std::map<EGLDisplay, std::pair<int, bool>> users;  // contexts alive, initialised by the library
};

DisplayUsers& display_users() {
  static DisplayUsers d;
  return d;
}

// eglInitialize unless the display is initialised already (then it is the
// host's, or an earlier EglContext's); counts this context as a user.
void initialize_display(EGLDisplay display) {
  DisplayUsers& d = display_users();
  const std::lock_guard lock(d.mutex);
  auto& [count, ours] = d.users[display];
  if (count == 0) {
    // An initialised display answers eglQueryString; an uninitialised one fails (EGL_NOT_INITIALIZED).
    const bool initialised = eglQueryString(display, EGL_VERSION) != nullptr;
    if (!initialised) {
      (void)eglGetError();  // the query's EGL_NOT_INITIALIZED, not ours to report
      EGLint major = 0, minor = 0;
      if (!eglInitialize(display, &major, &minor)) {
        d.users.erase(display);
        throw GlError(egl_error("eglInitialize"));
      }
    }
    ours = !initialised;
  }
  ++count;
}

// One user less; terminates the display after its last user, if the library initialised it.
void release_display(EGLDisplay display) {
  DisplayUsers& d = display_users();
  const std::lock_guard lock(d.mutex);
  const auto it = d.users.find(display);
  if (it == d.users.end()) return;
  if (--it->second.first > 0) return;
  const bool ours = it->second.second;
  d.users.erase(it);
  if (ours) eglTerminate(display);
}

}  // namespace

EglContext::EglContext(std::optional<int> device) {
  if (!device) device = device_from_env();
  EGLDisplay display = EGL_NO_DISPLAY;
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count) && count > 0) {
      const int index = device.value_or(0);
      if (index >= count)
        throw GlError("EGL device " + std::to_string(index) + " requested, only " + std::to_string(count) + " present");
      display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[index], nullptr);
      description_ = "EGL device " + std::to_string(index) + " of " + std::to_string(count) + " (EGL_EXT_platform_device)";
    }
  }
  if (display == EGL_NO_DISPLAY && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    description_ = "Mesa surfaceless (EGL_MESA_platform_surfaceless)";
  }
  if (display == EGL_NO_DISPLAY)
    throw GlError("no headless EGL display: neither EGL_EXT_platform_device nor EGL_MESA_platform_surfaceless works");
  initialize_display(display);
  if (!eglBindAPI(EGL_OPENGL_API)) {
    const std::string why = egl_error("eglBindAPI(OpenGL)");
    release_display(display);
    throw GlError(why);
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#if HABUFFER_GL_DEBUG
                               EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE,
#endif
                               EGL_NONE};
  context_ = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context_ == EGL_NO_CONTEXT) {
    context_ = nullptr;
    const std::string why = egl_error("creating an OpenGL 4.5 core context");
    release_display(display);
    throw GlError(why);
  }
  display_ = display;
  make_current();
  if (epoxy_has_gl_extension("GL_KHR_debug") || epoxy_gl_version() >= 43) install_debug_output();
}

void EglContext::make_current() {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) throw GlError(egl_error("eglMakeCurrent"));
}

void EglContext::release_current() {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT))
    throw GlError(egl_error("eglMakeCurrent (release)"));
}

EglContext::~EglContext() {
  if (display_ == nullptr) return;
  // Released only where it is current: a host context current here stays so.
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_ != nullptr) eglDestroyContext(display_, context_);
  release_display(display_);
}

}  // namespace habuffer::gl
