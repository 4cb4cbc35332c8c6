#include "habuffer/vk/techniques/arrays/vulkan_fixed_arrays.h"

#include <stdexcept>

#include "habuffer/shared/ha_constants.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/vk/vulkan_glsl.h"

namespace habuffer::vk {
namespace {

TechniqueConfig checked(const TechniqueConfig& c) {
  if (c.technique != Technique::Arrays)
    throw std::invalid_argument("VulkanFixedArrays holds arrays, not " + to_string(c.technique));
  c.validate();
  return c;
}

}  // namespace

VulkanFixedArrays::VulkanFixedArrays(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode)
    : VulkanTechnique(context, checked(config), mode) {
  check_atomic_mode(context, mode, config_.buffer.layout);
  counts_ = VulkanBuffer(context, config_.buffer.screen.area() * 4);
  layers_ = VulkanBuffer(context, capacity() * sizeof(glm::uvec2));
}

void VulkanFixedArrays::write_params(ParamBlock& p) const { write_technique_params(config_, p); }

std::vector<BoundBuffer> VulkanFixedArrays::buffers() const {
  const gl::GlBindings b = vulkan_bindings();
  return {{b.counts, &counts_}, {b.layers, &layers_}};
}

// The counts are zeroed; an entry is written before it is read.
void VulkanFixedArrays::record_clear(VkCommandBuffer cmd) const { counts_.record_zero(cmd); }

void VulkanFixedArrays::gathered(std::span<const std::uint32_t> counter_words) {
  most_arrived_ = counter_words[HABUFFER_COUNTER_MOST_ARRIVED];
}

std::uint64_t VulkanFixedArrays::capacity() const {
  return std::uint64_t{config_.layers} * config_.buffer.screen.area();
}

std::unique_ptr<FragmentBuffer> VulkanFixedArrays::read_back() const {
  auto arrays = std::make_unique<FixedArrays>(config_);
  arrays->import_state(counts_.read<std::uint32_t>(config_.buffer.screen.area()),
                       layers_.read<glm::uvec2>(capacity()), most_arrived_);
  return arrays;
}

}  // namespace habuffer::vk
