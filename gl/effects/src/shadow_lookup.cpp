#include "habuffer/gl/shadow_lookup.h"

#include <epoxy/gl.h>

#include <array>
#include <stdexcept>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/techniques/ha/gl_ha_table.h"
#include "lookup_points.h"

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

// A shared source under the prefix hs_: the light buffer's instance beside
// the view module's ha_ one (its environment in light_env.glsl).
std::string light_instance(const char* source) {
  const std::string renamed = replace_identifiers(replace_identifiers(source, "ha_", "hs_", false),
                                                  "habuffer_age_bits", "hs_age_bits", true);
  return replace_identifiers(renamed, "habuffer_coverage_bits", "hs_coverage_bits", true);
}

// The storage points, named as their members.
std::array<LookupPoint, 3> storage_points(const GlLightBindings& b) {
  return {LookupPoint{"table", b.table}, LookupPoint{"max_age", b.max_age}, LookupPoint{"offsets", b.offsets}};
}

}  // namespace

void GlLightBindings::validate(const GlBindings& view) const {
  validate_lookup_points("GlLightBindings", storage_points(*this), {"params", params}, view);
}

std::string GlLightBindings::glsl_defines(bool overridable) const {
  const std::array<LookupPoint, 3> s = storage_points(*this);
  const LookupPoint all[] = {s[0], s[1], s[2], {"params", params}};
  return lookup_defines("HABUFFER_LIGHT_BINDING_", all, overridable);
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
  light.check_context("GlShadowLookup");
  if (light.config().layout != Layout::L64)
    throw std::invalid_argument("a light buffer of L32 records carries no opacity: build it with L64 records");
  if (light.config().samples > 1)
    throw std::invalid_argument("a light buffer is one sample per pixel: its records' codes are depths alone "
                                "(this one has " + std::to_string(light.config().samples) + " samples)");
  bindings_.validate(view);
  params_ = GlStorage(sizeof(LightBlock));
  update(mapping);
  check_depths();
}

void GlShadowLookup::check_depths() const {
  if (!light_.gather_depth()) return;  // not gathered yet: bind() checks
  const std::string mismatch = light_depth_mismatch(*light_.gather_depth(), mapping_);
  if (!mismatch.empty()) throw GlError(mismatch);
}

void GlShadowLookup::update(const GlLightMapping& mapping) {
  light_.check_context("GlShadowLookup::update");
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
  light_.check_context("GlShadowLookup::bind");
  check_depths();
  if (light_.config().table != written_table_ || light_.config().screen != written_screen_) update(mapping_);
  light_.bind_for_lookup(bindings_.table, bindings_.max_age, bindings_.offsets);
  bind_at(GL_UNIFORM_BUFFER, bindings_.params, params_.id());
}

}  // namespace habuffer::gl
