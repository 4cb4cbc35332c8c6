// The HA-buffer on the GPU: its module parts, container and own shaders.
#include "habuffer/gl/techniques/ha/gl_ha_table.h"
#include "habuffer/gl/module_variant.h"
#include "habuffer/gl/technique_registry.h"
#include "ha_glsl.h"

namespace habuffer::gl {

std::string clear_pass_fragment(AtomicMode mode, const GlBindings& bindings) {
  return ha_module(mode, bindings, ShaderStage::Fragment) + kClearPassFragment;
}

}  // namespace habuffer::gl

namespace habuffer::gl::techniques::ha {
namespace {

std::string module_parts(AtomicMode mode) {
  return "#define HABUFFER_TECHNIQUE_CALL ha_call\n#define HABUFFER_TECHNIQUE_COMPOSITE ha_composite\n" +
         join_parts({kHaEnv, mode_prelude(mode), kHaRecord, kHaCarry, kSaturationEnv, kHaSaturation, kHaProbe,
                     kHaInsert, kHaBlend, kHaShadow, kHaTraverse, kHaEntry, kInsertEntry});
}

std::unique_ptr<GlTechnique> make(const TechniqueConfig& c, const OffsetSource& offsets, AtomicMode mode,
                                  const GlBindings& bindings, std::uint32_t clear_tile) {
  return std::make_unique<GlHaTable>(c.buffer, offsets, mode, bindings, clear_tile);
}

// The resume pass, the clear pass, and the entry in the variant furthest
// from the default (every #if branch the default leaves out), as the frame
// driver assembles it.
std::vector<ShaderSource> own_shaders(AtomicMode mode, const GlBindings& bindings) {
  ModuleVariant other;
  other.count_writes = true;
  other.slot_read_first = false;
  other.max_age_read_first = true;
  return {{"resume", "comp", resume_compute(mode, bindings)},
          {"full-screen", "vert", full_screen_vertex()},
          {"clear", "frag", clear_pass_fragment(mode, bindings)},
          {"insert-variant", "comp",
           technique_module(Technique::Ha, mode, bindings, ShaderStage::Compute, other.defines()) +
               kInsertStreamCompute},
          {"resume-variant", "comp",
           technique_module(Technique::Ha, mode, bindings, ShaderStage::Compute, other.defines()) + kResumeCompute}};
}

constexpr GlTechniqueDescriptor kDescriptor{Technique::Ha, module_parts, make, own_shaders, 1};

}  // namespace

const GlTechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::gl::techniques::ha
