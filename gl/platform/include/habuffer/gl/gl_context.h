/// @file
/// Which OpenGL context the calling thread has current, and the check every
/// library object makes with it: an object belongs to the context it was
/// made on. Each call on it checks first, before any GL call, that a
/// context is current (else a GL call would abort inside libepoxy or, once
/// its entry points were resolved, read zeros and loop) and that it is the
/// object's own (a sharing context shares buffers and programs but not the
/// vertex arrays and framebuffers the library's passes use; any other
/// context holds other objects under the same names), and throws a one-line
/// GlError otherwise. Destroyed while its context is not current (another
/// context current, none, or its context already gone), an object releases
/// nothing through GL: its names belong to a context this thread cannot
/// reach (the context's destruction frees them), never to the current one.
/// Contexts are known through EGL (eglGetCurrentContext) and GLX
/// (glXGetCurrentContext, when the process has loaded GLX).
#pragma once

namespace habuffer::gl {

/// The calling thread's current OpenGL context (an EGLContext or a
/// GLXContext), or nullptr when none is current.
const void* current_context();

/// Throws GlError "`call`: no OpenGL context is current on this thread" when
/// none is, and "`call`: OpenGL 4.5 is needed, this context is X.Y (...)"
/// below 4.5 (the library's shaders and direct state access need it).
void require_context(const char* call);

/// The context a GL name was made on, for its owner's destructor: release
/// the name only where current() (see the file comment). No check at
/// creation (the owner's maker checked).
struct MadeOn {
  const void* context = current_context();  ///< the context current at creation
  /// Whether that context is current on this thread.
  [[nodiscard]] bool current() const { return current_context() == context; }
};

/// The context an object was made on (see the file comment).
class ContextBound {
 public:
  /// Records the current context; require_context(`what`) first.
  explicit ContextBound(const char* what);
  /// Throws GlError naming `call` unless the object's context is current
  /// on this thread.
  void check(const char* call) const;
  /// Whether the object's context is current here (destructors: release
  /// GL names only then).
  [[nodiscard]] bool current() const;
  /// The context recorded.
  [[nodiscard]] const void* context() const { return context_; }

 private:
  const void* context_ = nullptr;
};

}  // namespace habuffer::gl
