/// @file
/// The linked lists on a Vulkan device (lists, sorted after the gather by
/// the sort pass; sorted-lists, kept sorted while inserting): the head
/// image, the node pool's entries and links, the saturation image of
/// sorted-lists, read back into the CPU's LinkedLists.
#pragma once

#include <cstdint>
#include <memory>

#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// One pool of fixed size on a device (lossless growth makes a larger one).
class VulkanLinkedLists final : public VulkanTechnique {
 public:
  /// Throws std::invalid_argument for a configuration the CPU would refuse
  /// (an automatic pool of 0 included: the build sizes it first),
  /// VulkanError for a mode the device cannot run or a pool beyond its
  /// storage range.
  VulkanLinkedLists(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode);

  void write_params(ParamBlock& p) const override;
  [[nodiscard]] std::vector<BoundBuffer> buffers() const override;
  void record_clear(VkCommandBuffer cmd) const override;
  void gathered(std::span<const std::uint32_t> counter_words) override;
  [[nodiscard]] std::uint64_t capacity() const override { return config_.pool_capacity; }
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  VulkanBuffer heads_, nodes_, links_, saturation_;
  std::uint64_t requested_ = 0;  ///< nodes the last gather asked for (the counter)
};

}  // namespace habuffer::vk
