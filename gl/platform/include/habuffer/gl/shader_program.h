/// @file
/// A linked GL program, built from source with every compile and link checked:
/// failures throw GlError carrying the driver's log.
#pragma once

#include <string>

#include "habuffer/gl/gl_context.h"

namespace habuffer::gl {

/// A linked GL program, deleted with the object (move-only).
class ShaderProgram {
 public:
  /// `name` labels errors ("insert compute shader: 0:12(3): error: ...").
  static ShaderProgram compute(const std::string& source, const std::string& name);
  /// A vertex and a fragment shader linked into one program; throws GlError
  /// with the log (compile errors name `name` and the stage).
  static ShaderProgram graphics(const std::string& vertex, const std::string& fragment, const std::string& name);
  /// Deletes the program (if any).
  ~ShaderProgram();
  /// Takes `o`'s program, leaving `o` empty (id 0).
  ShaderProgram(ShaderProgram&& o) noexcept;
  /// Deletes this program, then takes `o`'s, leaving `o` empty.
  ShaderProgram& operator=(ShaderProgram&& o) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  /// The GL program name (0 once moved from).
  [[nodiscard]] unsigned id() const { return id_; }
  /// Sets a uniform when the program uses it (unused ones are optimized away).
  void set(const char* name, unsigned value) const;
  /// The same for a uvec2 uniform.
  void set(const char* name, unsigned x, unsigned y) const;
  /// The same for a float uniform.
  void set(const char* name, float value) const;
  /// The same for a vec3 uniform.
  void set(const char* name, float x, float y, float z) const;

 private:
  explicit ShaderProgram(unsigned id) : id_(id) {}
  void release();  // deletes the program where its context is current (gl_context.h)
  unsigned id_ = 0;
  MadeOn made_on_;
};

}  // namespace habuffer::gl
