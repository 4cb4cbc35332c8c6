#include "habuffer/gl/shader_program.h"

#include <epoxy/gl.h>

#include <initializer_list>
#include <utility>

#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {
namespace {

// The info log of a shader or a program, read through the matching pair of
// GL entry points.
std::string info_log(GLuint object, void(GLAPIENTRY* get_iv)(GLuint, GLenum, GLint*),
                     void(GLAPIENTRY* get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint length = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  get_log(object, length, nullptr, log.data());
  return log.c_str();
}

std::string shader_log(GLuint shader) { return info_log(shader, glGetShaderiv, glGetShaderInfoLog); }
std::string program_log(GLuint program) { return info_log(program, glGetProgramiv, glGetProgramInfoLog); }

}  // namespace

namespace {

// Compiles one stage; throws with the log (the program is not made).
GLuint compile(GLenum stage, const std::string& source, const std::string& name) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = shader_log(shader);
    glDeleteShader(shader);
    discard_gl_errors();  // the log says it all
    throw GlError(name + " does not compile: " + log);
  }
  return shader;
}

GLuint link(std::initializer_list<GLuint> shaders, const std::string& name) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = program_log(program);
    glDeleteProgram(program);
    discard_gl_errors();
    throw GlError(name + " does not link: " + log);
  }
  return program;
}

}  // namespace

ShaderProgram ShaderProgram::compute(const std::string& source, const std::string& name) {
  return ShaderProgram(link({compile(GL_COMPUTE_SHADER, source, name)}, name));
}

ShaderProgram ShaderProgram::graphics(const std::string& vertex, const std::string& fragment, const std::string& name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex, name + " (vertex)");
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment, name + " (fragment)");
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return ShaderProgram(link({vs, fs}, name));
}

ShaderProgram::~ShaderProgram() { release(); }
void ShaderProgram::release() {
  if (id_ != 0 && made_on_.current()) glDeleteProgram(id_);
  id_ = 0;
}
ShaderProgram::ShaderProgram(ShaderProgram&& o) noexcept : id_(std::exchange(o.id_, 0)), made_on_(o.made_on_) {}
ShaderProgram& ShaderProgram::operator=(ShaderProgram&& o) noexcept {
  if (this != &o) {
    release();
    id_ = std::exchange(o.id_, 0);
    made_on_ = o.made_on_;
  }
  return *this;
}

void ShaderProgram::set(const char* name, unsigned value) const {
  const GLint loc = glGetUniformLocation(id_, name);
  if (loc >= 0) glProgramUniform1ui(id_, loc, value);
}
void ShaderProgram::set(const char* name, unsigned x, unsigned y) const {
  const GLint loc = glGetUniformLocation(id_, name);
  if (loc >= 0) glProgramUniform2ui(id_, loc, x, y);
}
void ShaderProgram::set(const char* name, float value) const {
  const GLint loc = glGetUniformLocation(id_, name);
  if (loc >= 0) glProgramUniform1f(id_, loc, value);
}

}  // namespace habuffer::gl

namespace habuffer::gl {

void ShaderProgram::set(const char* name, float x, float y, float z) const {
  const GLint loc = glGetUniformLocation(id_, name);
  if (loc >= 0) glProgramUniform3f(id_, loc, x, y, z);
}

}  // namespace habuffer::gl
