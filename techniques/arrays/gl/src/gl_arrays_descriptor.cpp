// Fixed per-pixel arrays on the GPU.
#include "arrays_glsl.h"
#include "habuffer/gl/techniques/arrays/gl_fixed_arrays.h"
#include "habuffer/gl/technique_registry.h"

namespace habuffer::gl::techniques::arrays {
namespace {

std::string module_parts(AtomicMode) {
  return "#define HABUFFER_TECHNIQUE_CALL fa_insert_fragment\n#define HABUFFER_TECHNIQUE_SORT fa_sort_pixel\n"
         "#define HABUFFER_TECHNIQUE_COMPOSITE fa_composite\n" +
         join_parts({kArraysEnv, kSortedEnv, kHaRecord, kHaBlend, kHaEntries, kArraysGlsl, kInsertEntry});
}

std::unique_ptr<GlTechnique> make(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                  const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlFixedArrays>(c, mode, bindings);
}

constexpr GlTechniqueDescriptor kDescriptor{Technique::Arrays, module_parts, make, nullptr, 3};

}  // namespace

const GlTechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::gl::techniques::arrays
