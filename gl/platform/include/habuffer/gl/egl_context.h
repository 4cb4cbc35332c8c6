/// @file
/// A headless OpenGL 4.5 core context through EGL: the device platform
/// (EGL_EXT_platform_device; device index from the constructor or the
/// HABUFFER_EGL_DEVICE environment variable), else Mesa's surfaceless
/// platform. No window and no X server. The library never assumes it owns
/// the current context: host apps make their own and skip this class.
#pragma once

#include <optional>
#include <string>

namespace habuffer::gl {

/// A headless OpenGL 4.5 core context made through EGL (see the file comment).
class EglContext {
 public:
  /// Creates the context and makes it current on this thread. Throws GlError
  /// with one line saying what was missing (EGL, a display, GL 4.5 core).
  explicit EglContext(std::optional<int> device = std::nullopt);
  /// Releases the context where it is current on this thread and destroys
  /// it. The display is terminated only after the last EglContext on it,
  /// and only if the library initialised it: a display the host had
  /// initialised first (its own contexts on the same EGL device) stays
  /// initialised, so the host's contexts keep working.
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes the context current on this thread; throws GlError when EGL refuses.
  void make_current();
  /// Releases the context from this thread (no context current here), so
  /// that another thread may make it current: EGL refuses a context current
  /// on a thread to every other one.
  void release_current();
  /// e.g. "EGL device 0 (EGL_EXT_platform_device)" or "Mesa surfaceless".
  [[nodiscard]] const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

}  // namespace habuffer::gl
