/// @file
/// The techniques the Vulkan path runs, each by its Vulkan part
/// (techniques/NAME/vk). So far the HA-buffer, lists, sorted lists and the
/// k-buffer; the others are refused by name (issue 48 adds them one by one).
#pragma once

#include <memory>
#include <string>

#include "habuffer/offset_source.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// Whether `t` has a Vulkan part.
bool runs_on_vulkan(Technique t);
/// The techniques that do, comma-separated ("ha, lists, sorted-lists, kbuffer").
std::string vulkan_technique_names();

/// A container of `config` on the context's device in `mode`. Throws
/// VulkanError naming the techniques the Vulkan path runs for any other.
std::unique_ptr<VulkanTechnique> make_vulkan_technique(const VulkanContext& context, const TechniqueConfig& config,
                                                       const OffsetSource& offsets, AtomicMode mode);

}  // namespace habuffer::vk
