// Linked lists on the GPU: `lists` (sorted by a sort pass) and
// `sorted-lists` (kept sorted while inserting), one container.
#include "linked_lists_glsl.h"
#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"
#include "habuffer/gl/technique_registry.h"

namespace habuffer::gl::techniques {
namespace {

std::string lists_parts(AtomicMode) {
  return "#define HABUFFER_TECHNIQUE_CALL ll_insert_fragment\n#define HABUFFER_TECHNIQUE_SORT ll_sort_pixel\n"
         "#define HABUFFER_TECHNIQUE_COMPOSITE ll_composite\n" +
         join_parts({kListsEnv, kSortedEnv, kHaRecord, kHaBlend, kHaEntries, kListsGlsl, kInsertEntry});
}

std::string sorted_lists_parts(AtomicMode) {
  return "#define HABUFFER_TECHNIQUE_CALL sl_insert_fragment\n#define HABUFFER_TECHNIQUE_COMPOSITE ll_composite\n"
         "#define HABUFFER_LISTS_QUALIFIER coherent\n" +
         join_parts({kListsEnv, kSortedListsEnv, kSortedEnv, kHaRecord, kHaBlend, kHaEntries, kListsGlsl, kSaturationEnv,
                     kHaSaturation, kSortedListsGlsl, kInsertEntry});
}

std::unique_ptr<GlTechnique> make_lists(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                        const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlLinkedLists>(c, lists_kind(), mode, bindings);
}

std::unique_ptr<GlTechnique> make_sorted_lists(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                               const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlLinkedLists>(c, sorted_lists_kind(), mode, bindings);
}

constexpr GlTechniqueDescriptor kLists{Technique::Lists, lists_parts, make_lists, nullptr, 2};
constexpr GlTechniqueDescriptor kSortedLists{Technique::SortedLists, sorted_lists_parts, make_sorted_lists, nullptr, 2};

}  // namespace

namespace lists {
const GlTechniqueDescriptor& descriptor() { return kLists; }
}  // namespace lists
namespace sorted_lists {
const GlTechniqueDescriptor& descriptor() { return kSortedLists; }
}  // namespace sorted_lists

}  // namespace habuffer::gl::techniques
