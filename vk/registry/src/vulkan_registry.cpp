#include "habuffer/vk/vulkan_registry.h"

#include "habuffer/vk/techniques/arrays/vulkan_fixed_arrays.h"
#include "habuffer/vk/techniques/ha/vulkan_ha_table.h"
#include "habuffer/vk/techniques/kbuffer/vulkan_kbuffer.h"
#include "habuffer/vk/techniques/linked_lists/vulkan_linked_lists.h"
#include "habuffer/vk/techniques/paged_lists/vulkan_paged_lists.h"
#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {
namespace {

// One line a technique: its Vulkan part's maker.
using Maker = std::unique_ptr<VulkanTechnique> (*)(const VulkanContext&, const TechniqueConfig&, const OffsetSource&,
                                                   AtomicMode);
struct Entry {
  Technique technique;
  Maker make;
};
constexpr Entry kEntries[] = {
    {Technique::Ha,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource& o, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return std::make_unique<VulkanHaTable>(c, t, o, m); }},
    {Technique::Lists,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource&, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return std::make_unique<VulkanLinkedLists>(c, t, m); }},
    {Technique::SortedLists,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource&, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return std::make_unique<VulkanLinkedLists>(c, t, m); }},
    {Technique::Arrays,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource&, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return std::make_unique<VulkanFixedArrays>(c, t, m); }},
    {Technique::KBuffer,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource&, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return std::make_unique<VulkanKBuffer>(c, t, m); }},
    {Technique::PagedLists,
     [](const VulkanContext& c, const TechniqueConfig& t, const OffsetSource&, AtomicMode m)
         -> std::unique_ptr<VulkanTechnique> { return make_vulkan_paged_lists(c, t, m); }},
};

}  // namespace

bool runs_on_vulkan(Technique t) {
  for (const Entry& e : kEntries)
    if (e.technique == t) return true;
  return false;
}

std::string vulkan_technique_names() {
  std::string names;
  for (const Entry& e : kEntries) names += (names.empty() ? "" : ", ") + to_string(e.technique);
  return names;
}

std::unique_ptr<VulkanTechnique> make_vulkan_technique(const VulkanContext& context, const TechniqueConfig& config,
                                                       const OffsetSource& offsets, AtomicMode mode) {
  for (const Entry& e : kEntries)
    if (e.technique == config.technique) return e.make(context, config, offsets, mode);
  throw VulkanError("the Vulkan path does not run " + to_string(config.technique) + " yet (it runs " +
                    vulkan_technique_names() + ")");
}

}  // namespace habuffer::vk
