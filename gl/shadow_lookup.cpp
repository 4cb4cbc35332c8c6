#include "habuffer/gl/shadow_lookup.h"

#include <epoxy/gl.h>

#include <cctype>
#include <string_view>
#include <utility>
#include <stdexcept>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/techniques/ha/gl_ha_table.h"

namespace habuffer::gl {
namespace {

// The block HabufferLight of light_env.glsl, std140.
struct LightBlock {
  glm::mat4 view;
  glm::mat4 projection;
  std::uint32_t table_size[2];
  std::uint32_t map_size[2];
  std::uint32_t age_bits, block, max_age_cells_x, bias;
  float near_plane, far_plane;
  std::uint32_t pad[2];
};
static_assert(sizeof(LightBlock) == 176, "HabufferLight's std140 layout (light_env.glsl)");

bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// Replaces `from` where it starts an identifier (and, when `whole`, where it
// is the whole identifier). Hand-written rather than std::regex: GCC 12's
// <regex> trips -Wmaybe-uninitialized under -fsanitize=address with -Werror.
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

// A shared source under the prefix hs_: the light buffer's instance beside
// the view module's ha_ one (its environment in light_env.glsl).
std::string light_instance(const char* source) {
  return replace_identifiers(replace_identifiers(source, "ha_", "hs_", false), "habuffer_age_bits", "hs_age_bits",
                             true);
}

}  // namespace

void GlLightBindings::validate(const GlBindings& view) const {
  const unsigned points[] = {table, max_age, offsets};
  const char* names[] = {"table", "max_age", "offsets"};
  GLint max_storage = 0, max_uniform = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_storage);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &max_uniform);
  const std::vector<unsigned> taken = view.storage_points();
  for (int i = 0; i < 3; ++i) {
    if (points[i] >= static_cast<unsigned>(max_storage))
      throw GlError(std::string("shader-storage binding point GlLightBindings::") + names[i] + " = " +
                    std::to_string(points[i]) + " is beyond this context's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS (" +
                    std::to_string(max_storage) + ")");
    for (const unsigned p : taken)
      if (p == points[i])
        throw GlError(std::string("GlLightBindings::") + names[i] + " = " + std::to_string(p) +
                      " is a point of the view's GlBindings");
    for (int j = i + 1; j < 3; ++j)
      if (points[i] == points[j])
        throw GlError(std::string("GlLightBindings::") + names[i] + " and ::" + names[j] + " are both " +
                      std::to_string(points[i]));
  }
  if (params >= static_cast<unsigned>(max_uniform) || params == view.params)
    throw GlError("uniform-buffer binding point GlLightBindings::params = " + std::to_string(params) +
                  " is the view's or beyond this context's GL_MAX_UNIFORM_BUFFER_BINDINGS (" +
                  std::to_string(max_uniform) + ")");
}

std::string GlLightBindings::glsl_defines(bool overridable) const {
  std::string s;
  for (const auto& [name, point] : {std::pair{"TABLE", table}, std::pair{"MAX_AGE", max_age},
                                    std::pair{"OFFSETS", offsets}, std::pair{"PARAMS", params}}) {
    const std::string macro = std::string("HABUFFER_LIGHT_BINDING_") + name;
    if (overridable) s += "#ifndef " + macro + "\n";
    s += "#define " + macro + " " + std::to_string(point) + "\n";
    if (overridable) s += "#endif\n";
  }
  return s;
}

std::string light_lookup_part(const GlLightBindings& bindings, AtomicMode mode, bool overridable) {
  if (mode == AtomicMode::Native32)
    throw GlError("the light lookup reads 64-bit records: atomic mode native32 has no 64-bit shader integers "
                  "(use native64 or emulated64)");
  std::string s = bindings.glsl_defines(overridable);
  s += kLightEnv;
  for (const char* shared : {kHaRecord, kHaProbe, kHaBlend, kHaShadow, kHaShadowPcf, kHaTraverse}) s += light_instance(shared) + "\n";
  return s + kHaLightMap + "\n" + kLightLookup;
}

std::string light_lookup_shader_head(const GlLightBindings& bindings, AtomicMode mode) {
  std::string part = light_lookup_part(bindings, mode);  // refuses native32 first
  return "#version 450 core\n" + module_extensions(mode) + kHaConstants + "\n" + kGlslEnv + "\n" + part;
}

GlShadowLookup::GlShadowLookup(const GlHaTable& light, const GlLightMapping& mapping, std::uint32_t bias,
                               const GlBindings& view, const GlLightBindings& bindings)
    : light_(light), bindings_(bindings), bias_(bias) {
  if (light.config().layout != Layout::L64)
    throw std::invalid_argument("a light buffer of L32 records carries no opacity: build it with L64 records");
  bindings_.validate(view);
  params_ = GlStorage(sizeof(LightBlock));
  update(mapping);
}

void GlShadowLookup::update(const GlLightMapping& mapping) {
  mapping_ = mapping;
  const BufferConfig& c = light_.config();
  written_table_ = c.table;
  written_screen_ = c.screen;
  LightBlock b{};
  b.view = mapping.view;
  b.projection = mapping.projection;
  b.table_size[0] = c.table.x;
  b.table_size[1] = c.table.y;
  b.map_size[0] = c.screen.x;
  b.map_size[1] = c.screen.y;
  b.age_bits = c.age_bits;
  b.block = c.block;
  b.max_age_cells_x = (c.screen.x - 1) / c.block + 1;
  b.bias = bias_;
  b.near_plane = mapping.near_plane;
  b.far_plane = mapping.far_plane;
  glNamedBufferSubData(params_.id(), 0, sizeof b, &b);
}

void GlShadowLookup::bind() {
  if (light_.config().table != written_table_ || light_.config().screen != written_screen_) update(mapping_);
  light_.bind_for_lookup(bindings_.table, bindings_.max_age, bindings_.offsets);
  bind_at(GL_UNIFORM_BUFFER, bindings_.params, params_.id());
}

}  // namespace habuffer::gl
