#include "habuffer/gl/debug_output.h"

#include <epoxy/gl.h>

#include <cstdio>
#include <mutex>
#include <set>
#include <vector>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {
namespace {

struct DebugState {
  std::mutex mutex;
  LogSink sink = [](const std::string& m) { std::fprintf(stderr, "habuffer gl: %s\n", m.c_str()); };
  bool raise = HABUFFER_GL_DEBUG;
  std::vector<std::string> errors;
  std::set<std::string> noted;  // warnings already passed to the sink (their text and id)
};

DebugState& state() {
  static DebugState s;
  return s;
}

void GLAPIENTRY on_message(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei length, const GLchar* text,
                           const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  const std::string message = std::string(text, length >= 0 ? static_cast<std::size_t>(length) : std::string(text).size()) +
                              " (id " + std::to_string(id) + ")";
  DebugState& s = state();
  const std::lock_guard lock(s.mutex);
  if (type == GL_DEBUG_TYPE_ERROR) {
    s.errors.push_back(message);
  } else if (!s.noted.insert(message).second) {
    return;  // each warning once per process: a driver repeats its performance notes every frame
  }
  if (s.sink) s.sink(message);
}

}  // namespace

void set_log_sink(LogSink sink) {
  const std::lock_guard lock(state().mutex);
  state().sink = std::move(sink);
}

void log_once(const std::string& message) {
  DebugState& s = state();
  const std::lock_guard lock(s.mutex);
  if (!s.noted.insert(message).second) return;
  if (s.sink) s.sink(message);
}

void set_throw_on_gl_error(bool enabled) {
  const std::lock_guard lock(state().mutex);
  state().raise = enabled;
}

void install_debug_output() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // errors are reported on the call that caused them
  glDebugMessageCallback(on_message, nullptr);
}

void discard_gl_errors() {
  const std::lock_guard lock(state().mutex);
  state().errors.clear();
}

void check_gl_errors(const char* where) {
  DebugState& s = state();
  std::vector<std::string> errors;
  bool raise = false;
  {
    const std::lock_guard lock(s.mutex);
    errors.swap(s.errors);
    raise = s.raise;
  }
  if (!raise || errors.empty()) return;
  std::string all;
  for (const auto& e : errors) all += (all.empty() ? "" : "; ") + e;
  throw GlError(std::string(where) + ": GL error: " + all);
}

}  // namespace habuffer::gl
