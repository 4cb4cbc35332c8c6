/// @file
/// KHR_debug routing for contexts the library creates (EglContext): driver
/// messages go to a log sink (stderr by default; every error, each other
/// message once per process, notifications never), and GL
/// errors are collected
/// so check_gl_errors() can raise them as GlError. Raising is on by default in
/// debug builds and can be switched at run time. Host contexts are left
/// untouched: the library never installs a callback on a context it did not make.
#pragma once

#include <functional>
#include <string>

namespace habuffer::gl {

/// Receives every driver message except notifications, with " (id N)" appended.
using LogSink = std::function<void(const std::string& message)>;
/// Replaces the sink (default: stderr, prefixed "habuffer gl: "); an empty sink
/// drops the messages.
void set_log_sink(LogSink sink);
/// Whether check_gl_errors() throws (default: on where the library was built
/// with HABUFFER_GL_DEBUG, as Debug builds and the asan preset are, off
/// otherwise); errors are collected either way.
void set_throw_on_gl_error(bool enabled);

/// Passes a message of the library's own (a warning) to the sink, once per
/// process for each text, as driver warnings are.
void log_once(const std::string& message);

/// Installs the callback on the current context (needs KHR_debug / GL 4.3).
void install_debug_output();
/// Throws GlError naming `where` and the collected error messages when raising
/// is enabled; clears the collected errors either way.
void check_gl_errors(const char* where);
/// Forgets collected errors already reported another way (a shader's log).
void discard_gl_errors();

}  // namespace habuffer::gl
