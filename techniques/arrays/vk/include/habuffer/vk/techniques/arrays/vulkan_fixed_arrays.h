/// @file
/// Fixed per-pixel arrays on a Vulkan device: each pixel's count and its K
/// entries (sorted after the gather by the sort pass), read back into the
/// CPU's FixedArrays.
#pragma once

#include <cstdint>
#include <memory>

#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// K entries a pixel on a device (lossless growth makes a larger K).
class VulkanFixedArrays final : public VulkanTechnique {
 public:
  /// Throws std::invalid_argument for a configuration the CPU would refuse,
  /// VulkanError for a mode the device cannot run or layers beyond its
  /// storage range.
  VulkanFixedArrays(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode);

  void write_params(ParamBlock& p) const override;
  [[nodiscard]] std::vector<BoundBuffer> buffers() const override;
  void record_clear(VkCommandBuffer cmd) const override;
  void gathered(std::span<const std::uint32_t> counter_words) override;
  [[nodiscard]] std::uint64_t capacity() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  VulkanBuffer counts_, layers_;
  std::uint32_t most_arrived_ = 0;  ///< the most fragments a pixel received, where some pixel overflowed
};

}  // namespace habuffer::vk
