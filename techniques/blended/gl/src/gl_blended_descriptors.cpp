// The blended baselines on the GPU: weighted blended OIT and plain blending,
// one container drawing through the fixed-function blender.
#include "blended_glsl.h"
#include "habuffer/gl/techniques/blended/gl_blended_image.h"
#include "habuffer/gl/technique_registry.h"

namespace habuffer::gl::techniques {
namespace {

const char* const kBlendedMacros =
    "#define HABUFFER_TECHNIQUE_BEGIN bl_begin_call\n#define HABUFFER_TECHNIQUE_CALL bl_insert_fragment\n"
    "#define HABUFFER_TECHNIQUE_COMPOSITE bl_composite\n";

std::string blend_parts(AtomicMode) {
  return kBlendedMacros + join_parts({kBlendedEnv, kHaRecord, kHaBlend, kBlendedGlsl, kBlendedEntry, kInsertEntry});
}

std::string wboit_parts(AtomicMode mode) { return "#define HABUFFER_WBOIT\n" + blend_parts(mode); }

std::unique_ptr<GlTechnique> make(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                  const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlBlendedImage>(c, mode, bindings);
}

constexpr GlTechniqueDescriptor kWboit{Technique::Wboit, wboit_parts, make, nullptr, 5};
constexpr GlTechniqueDescriptor kBlend{Technique::Blend, blend_parts, make, nullptr, 5};

}  // namespace

namespace wboit {
const GlTechniqueDescriptor& descriptor() { return kWboit; }
}  // namespace wboit
namespace blend {
const GlTechniqueDescriptor& descriptor() { return kBlend; }
}  // namespace blend

}  // namespace habuffer::gl::techniques
