#include "habuffer/gl/gl_bindings.h"

#include <algorithm>
#include <cctype>
#include <string>

#include <epoxy/gl.h>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {

std::string GlBindings::macro_name(const char* point) {
  std::string macro = std::string("HABUFFER_BINDING_") + point;
  std::transform(macro.begin(), macro.end(), macro.begin(), [](unsigned char c) { return std::toupper(c); });
  return macro;
}

std::span<const GlBindings::Point> GlBindings::points() {
  static constexpr Point kPoints[] = {
      {"counters", &GlBindings::counters, 0},  {"locks", &GlBindings::locks, 0},
      {"capture", &GlBindings::capture, 0},    {"stream", &GlBindings::stream, 0},
      {"deferred", &GlBindings::deferred, 0},  {"saturation", &GlBindings::saturation, 0},
      {"table", &GlBindings::table, 1},        {"max_age", &GlBindings::max_age, 1},
      {"offsets", &GlBindings::offsets, 1},    {"heads", &GlBindings::heads, 2},
      {"nodes", &GlBindings::nodes, 2},        {"links", &GlBindings::links, 2},
      {"counts", &GlBindings::counts, 3},      {"layers", &GlBindings::layers, 3},
      {"slots", &GlBindings::slots, 4},        {"occupancy", &GlBindings::occupancy, 4},
      {"limits", &GlBindings::limits, 4},      {"accum", &GlBindings::accum, 5},
      {"revealage", &GlBindings::revealage, 5}};
  return kPoints;
}

std::vector<unsigned> GlBindings::storage_points() const {
  std::vector<unsigned> out;
  for (const Point& p : points()) out.push_back(this->*p.member);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void GlBindings::validate() const {
  const auto all = points();
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const bool together = all[i].group == 0 || all[j].group == 0 || all[i].group == all[j].group;
      if (together && this->*all[i].member == this->*all[j].member)
        throw GlError(std::string("shader-storage binding point ") + std::to_string(this->*all[i].member) +
                      " is used twice (GlBindings::" + all[i].name + " and ::" + all[j].name + ")");
    }
  GLint max_storage = 0, max_uniform = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_storage);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &max_uniform);
  // Points run from 0 to the limit - 1: a point equal to the limit is out.
  for (const Point& p : all)
    if (this->*p.member >= static_cast<unsigned>(max_storage))
      throw GlError(std::string("shader-storage binding point GlBindings::") + p.name + " = " +
                    std::to_string(this->*p.member) +
                    " is beyond this context's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS (" + std::to_string(max_storage) +
                    ": points 0.." + std::to_string(max_storage - 1) + ")");
  if (params >= static_cast<unsigned>(max_uniform))
    throw GlError("uniform-buffer binding point GlBindings::params = " + std::to_string(params) +
                  " is beyond this context's GL_MAX_UNIFORM_BUFFER_BINDINGS (" + std::to_string(max_uniform) +
                  ": points 0.." + std::to_string(max_uniform - 1) + ")");
}

GlBindings GlBindings::from_base(unsigned storage_base, unsigned uniform_base) {
  GlBindings b;
  unsigned shared = storage_base + kTechniquePoints;
  unsigned group = 0, next = storage_base;
  for (const Point& p : points()) {
    if (p.group == 0) {
      b.*p.member = shared++;
      continue;
    }
    if (p.group != group) next = storage_base;  // each technique's buffers from the base
    group = p.group;
    b.*p.member = next++;
  }
  b.params = uniform_base;
  return b;
}

std::string GlBindings::glsl_defines(bool overridable) const {
  std::string s;
  const auto define = [&](const char* name, unsigned v) {
    const std::string macro = macro_name(name);
    if (overridable) s += "#ifndef " + macro + '\n';
    s += "#define " + macro + ' ' + std::to_string(v) + '\n';
    if (overridable) s += "#endif\n";
  };
  for (const Point& p : points()) define(p.name, this->*p.member);
  define("params", params);
  return s;
}

}  // namespace habuffer::gl
