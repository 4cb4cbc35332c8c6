// The k-buffer on the GPU: its module parts, container and the occupancy
// map's count pass and resume pass.
#include "ha_glsl.h"
#include "kbuffer_glsl.h"
#include "habuffer/gl/techniques/kbuffer/gl_kbuffer.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/technique_registry.h"

namespace habuffer::gl {

std::string kbuffer_count_compute(AtomicMode mode, const GlBindings& bindings) {
  return technique_module(Technique::KBuffer, mode, bindings, ShaderStage::Compute) + kKBufferCountCompute;
}

}  // namespace habuffer::gl

namespace habuffer::gl::techniques::kbuffer {
namespace {

std::string module_parts(AtomicMode mode) {
  return "#define HABUFFER_TECHNIQUE_CALL kb_call\n#define HABUFFER_TECHNIQUE_COMPOSITE kb_composite\n"
         "#define HABUFFER_CARRY_RUN kb_insert_run\n" +
         join_parts({kKBufferEnv, mode_prelude(mode), kHaRecord, kHaCarry, kSaturationEnv, kHaSaturation, kHaBlend,
                     kKBufferGlsl, kHaEntry, kKBufferEntry, kInsertEntry});
}

std::unique_ptr<GlTechnique> make(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                  const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlKBuffer>(c, mode, bindings);
}

std::vector<ShaderSource> own_shaders(AtomicMode mode, const GlBindings& bindings) {
  return {{"kbuffer-count", "comp", kbuffer_count_compute(mode, bindings)},
          {"kbuffer-resume", "comp", resume_compute(Technique::KBuffer, mode, bindings)}};
}

constexpr GlTechniqueDescriptor kDescriptor{Technique::KBuffer, module_parts, make, own_shaders, 4};

}  // namespace

const GlTechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::gl::techniques::kbuffer
