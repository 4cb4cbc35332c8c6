// Paged lists on the GPU: the linked lists' buffers and environment
// (lists_env.glsl), pages of nodes (paged_lists_env.glsl, paged_lists.glsl),
// the linked lists' sort pass and compositing (lists.glsl).
#include <string>

#include "habuffer/gl/technique_registry.h"
#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "linked_lists_glsl.h"
#include "paged_lists_glsl.h"
#include "habuffer/techniques/paged_lists/detail/paged_lists_kernel.h"

namespace habuffer::gl::techniques {
namespace {

std::string paged_lists_parts(AtomicMode) {
  return "#define HABUFFER_TECHNIQUE_CALL pl_insert_fragment\n#define HABUFFER_TECHNIQUE_SORT pl_sort_pixel\n"
         "#define HABUFFER_TECHNIQUE_COMPOSITE ll_composite\n#define HABUFFER_LISTS_QUALIFIER coherent\n"
         "#define HABUFFER_PAGE_NODES " +
         std::to_string(kPagedListsPageNodes) + "u\n" +
         join_parts({kListsEnv, kPagedListsEnv, kSortedEnv, kHaRecord, kHaBlend, kHaEntries, kListsGlsl, kPagedListsGlsl,
                     kInsertEntry});
}

// The linked lists' container, taking pages of nodes (paged_lists.glsl).
constexpr GlNodeListKind kPagedKind{Technique::PagedLists, kPagedListsPageNodes, true, import_node_lists<PagedLists>};

std::unique_ptr<GlTechnique> make(const TechniqueConfig& c, const OffsetSource&, AtomicMode mode,
                                  const GlBindings& bindings, std::uint32_t) {
  return std::make_unique<GlLinkedLists>(c, kPagedKind, mode, bindings);
}

constexpr GlTechniqueDescriptor kPagedLists{Technique::PagedLists, paged_lists_parts, make, nullptr, 2};

}  // namespace

namespace paged_lists {
const GlTechniqueDescriptor& descriptor() { return kPagedLists; }
}  // namespace paged_lists

}  // namespace habuffer::gl::techniques
