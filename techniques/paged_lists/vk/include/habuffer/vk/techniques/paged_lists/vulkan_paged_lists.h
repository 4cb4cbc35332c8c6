/// @file
/// Paged lists on a Vulkan device: the linked lists' buffers
/// (VulkanLinkedLists), nodes taken a page at a time by the shared GLSL,
/// read back into the CPU's PagedLists.
#pragma once

#include <memory>

#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// A paged-lists container of `config` (its pool given, in nodes) on the
/// context's device. Throws as VulkanLinkedLists does.
std::unique_ptr<VulkanTechnique> make_vulkan_paged_lists(const VulkanContext& context, const TechniqueConfig& config,
                                                         AtomicMode mode);

}  // namespace habuffer::vk
