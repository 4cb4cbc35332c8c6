/// @file
/// A linked GL program, built from source with every compile and link checked:
/// failures throw GlError carrying the driver's log.
#pragma once

#include <string>

namespace habuffer::gl {

class ShaderProgram {
 public:
  /// `name` labels errors ("insert compute shader: 0:12(3): error: ...").
  static ShaderProgram compute(const std::string& source, const std::string& name);
  static ShaderProgram graphics(const std::string& vertex, const std::string& fragment, const std::string& name);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& o) noexcept;
  ShaderProgram& operator=(ShaderProgram&& o) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  [[nodiscard]] unsigned id() const { return id_; }
  /// Sets a uniform when the program uses it (unused ones are optimized away).
  void set(const char* name, unsigned value) const;
  void set(const char* name, unsigned x, unsigned y) const;
  void set(const char* name, float value) const;
  void set(const char* name, float x, float y, float z) const;

 private:
  explicit ShaderProgram(unsigned id) : id_(id) {}
  unsigned id_ = 0;
};

}  // namespace habuffer::gl
