/// @file
/// The techniques the Vulkan path runs, each by its Vulkan part
/// (techniques/NAME/vk): the HA-buffer, lists, sorted lists, fixed arrays,
/// the k-buffer and paged lists. The blended baselines (wboit, blend), which
/// blend in a framebuffer, are refused by name.
#pragma once

#include <memory>
#include <string>

#include "habuffer/offset_source.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// Whether `t` has a Vulkan part.
bool runs_on_vulkan(Technique t);
/// The techniques that do, comma-separated ("ha, lists, sorted-lists, arrays, kbuffer, paged-lists").
std::string vulkan_technique_names();

/// A container of `config` on the context's device in `mode`. Throws
/// VulkanError naming the techniques the Vulkan path runs for any other.
std::unique_ptr<VulkanTechnique> make_vulkan_technique(const VulkanContext& context, const TechniqueConfig& config,
                                                       const OffsetSource& offsets, AtomicMode mode);

}  // namespace habuffer::vk
