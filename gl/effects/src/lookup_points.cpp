#include "lookup_points.h"

#include <epoxy/gl.h>

#include <cctype>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {
namespace {

bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

}  // namespace

// Hand-written rather than std::regex: GCC 12's <regex> trips
// -Wmaybe-uninitialized under -fsanitize=address with -Werror.
std::string replace_identifiers(std::string_view source, std::string_view from, std::string_view to, bool whole) {
  std::string out;
  out.reserve(source.size());
  std::size_t i = 0;
  while (i < source.size()) {
    const bool starts = source.compare(i, from.size(), from) == 0 && (i == 0 || !is_identifier_char(source[i - 1]));
    const std::size_t end = i + from.size();
    if (starts && (!whole || end >= source.size() || !is_identifier_char(source[end]))) {
      out += to;
      i = end;
    } else {
      out += source[i++];
    }
  }
  return out;
}

void validate_lookup_points(const char* type, std::span<const LookupPoint> storage, LookupPoint uniform,
                            const GlBindings& view) {
  GLint max_storage = 0, max_uniform = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_storage);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &max_uniform);
  const std::vector<unsigned> taken = view.storage_points();
  const std::string name = type;
  for (std::size_t i = 0; i < storage.size(); ++i) {
    const LookupPoint& p = storage[i];
    if (p.point >= static_cast<unsigned>(max_storage))
      throw GlError("shader-storage binding point " + name + "::" + p.name + " = " + std::to_string(p.point) +
                    " is beyond this context's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS (" + std::to_string(max_storage) +
                    ")");
    for (const unsigned t : taken)
      if (t == p.point)
        throw GlError(name + "::" + p.name + " = " + std::to_string(t) + " is a point of the view's GlBindings");
    for (std::size_t j = i + 1; j < storage.size(); ++j)
      if (p.point == storage[j].point)
        throw GlError(name + "::" + p.name + " and ::" + storage[j].name + " are both " + std::to_string(p.point));
  }
  if (uniform.point >= static_cast<unsigned>(max_uniform) || uniform.point == view.params)
    throw GlError("uniform-buffer binding point " + name + "::" + uniform.name + " = " + std::to_string(uniform.point) +
                  " is the view's or beyond this context's GL_MAX_UNIFORM_BUFFER_BINDINGS (" +
                  std::to_string(max_uniform) + ")");
}

std::string lookup_defines(std::string_view prefix, std::span<const LookupPoint> points, bool overridable) {
  std::string s;
  for (const LookupPoint& p : points) {
    std::string macro(prefix);
    for (const char* c = p.name; *c != '\0'; ++c) macro += static_cast<char>(std::toupper(static_cast<unsigned char>(*c)));
    if (overridable) s += "#ifndef " + macro + "\n";
    s += "#define " + macro + " " + std::to_string(p.point) + "\n";
    if (overridable) s += "#endif\n";
  }
  return s;
}

}  // namespace habuffer::gl
