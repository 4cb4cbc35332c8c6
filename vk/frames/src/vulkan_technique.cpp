#include "habuffer/vk/vulkan_technique.h"

#include <algorithm>

#include "habuffer/shared/ha_constants.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {

bool VulkanTechnique::sorts_after_gather() const { return !descriptor(config_.technique).sorted_on_insert; }

std::uint64_t emulated64_lock_bytes(AtomicMode mode, std::uint64_t slots) {
  return mode == AtomicMode::Emulated64 ? std::max<std::uint64_t>(emulated64_lock_words(slots), 1) * 4 : 4;
}

void check_atomic_mode(const VulkanContext& context, AtomicMode mode, Layout layout) {
  if ((mode == AtomicMode::Native32) != (layout == Layout::L32))
    throw VulkanError("atomic mode " + to_string(mode) + " does not hold " + to_string(layout) + " records");
  const VulkanInfo& info = context.info();
  if (mode != AtomicMode::Native32 && !info.shader_int64)
    throw VulkanError("atomic mode " + to_string(mode) + " needs 64-bit shader integers (shaderInt64), which " +
                      info.name + " lacks");
  if (mode == AtomicMode::Native64 && !info.buffer_int64_atomics)
    throw VulkanError("atomic mode native64 needs 64-bit buffer atomics (shaderBufferInt64Atomics), which " +
                      info.name + " lacks");
}

}  // namespace habuffer::vk
