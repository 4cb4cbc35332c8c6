#include "habuffer/vk/techniques/paged_lists/vulkan_paged_lists.h"

#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "habuffer/vk/techniques/linked_lists/vulkan_linked_lists.h"

namespace habuffer::vk {
namespace {

std::unique_ptr<FragmentBuffer> import_paged(const TechniqueConfig& config, std::span<const std::uint32_t> heads,
                                             std::span<const glm::uvec2> entries, std::span<const std::uint32_t> links,
                                             std::uint64_t requested) {
  auto lists = std::make_unique<PagedLists>(config);
  lists->import_state(heads, entries, links, requested);
  return lists;
}

constexpr VulkanNodeListKind kPagedKind{Technique::PagedLists, import_paged};

}  // namespace

std::unique_ptr<VulkanTechnique> make_vulkan_paged_lists(const VulkanContext& context, const TechniqueConfig& config,
                                                         AtomicMode mode) {
  return std::make_unique<VulkanLinkedLists>(context, config, kPagedKind, mode);
}

}  // namespace habuffer::vk
