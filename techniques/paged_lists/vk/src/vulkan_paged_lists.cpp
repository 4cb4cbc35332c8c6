#include "habuffer/vk/techniques/paged_lists/vulkan_paged_lists.h"

#include "habuffer/techniques/linked_lists/import_node_lists.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "habuffer/vk/techniques/linked_lists/vulkan_linked_lists.h"

namespace habuffer::vk {
namespace {

constexpr VulkanNodeListKind kPagedKind{Technique::PagedLists, import_node_lists<PagedLists>};

}  // namespace

std::unique_ptr<VulkanTechnique> make_vulkan_paged_lists(const VulkanContext& context, const TechniqueConfig& config,
                                                         AtomicMode mode) {
  return std::make_unique<VulkanLinkedLists>(context, config, kPagedKind, mode);
}

}  // namespace habuffer::vk
