#include <stdexcept>

#include "habuffer/gl/gl_blended_image.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_fixed_arrays.h"
#include "habuffer/gl/gl_ha_table.h"
#include "habuffer/gl/gl_kbuffer.h"
#include "habuffer/gl/gl_linked_lists.h"

namespace habuffer::gl {

std::unique_ptr<GlTechnique> make_gl_technique(const TechniqueConfig& c, const OffsetSource& offsets, AtomicMode mode,
                                               const GlBindings& bindings, std::uint32_t clear_tile) {
  switch (c.technique) {
    case Technique::Ha: return std::make_unique<GlHaTable>(c.buffer, offsets, mode, bindings, clear_tile);
    case Technique::Lists: return std::make_unique<GlLinkedLists>(c, mode, bindings);
    case Technique::Arrays: return std::make_unique<GlFixedArrays>(c, mode, bindings);
    case Technique::SortedLists: return std::make_unique<GlLinkedLists>(c, mode, bindings);
    case Technique::KBuffer: return std::make_unique<GlKBuffer>(c, mode, bindings);
    case Technique::Wboit:
    case Technique::Blend: return std::make_unique<GlBlendedImage>(c, mode, bindings);
  }
  throw std::invalid_argument("unknown technique");
}

}  // namespace habuffer::gl
