/// @file
/// The linked lists on a Vulkan device (lists, sorted after the gather by
/// the sort pass; sorted-lists, kept sorted while inserting): the head
/// image, the node pool's entries and links, the saturation image of
/// sorted-lists, read back into the CPU's LinkedLists.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include <glm/vec2.hpp>

#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// Which node lists a VulkanLinkedLists holds: the technique, and the CPU
/// container its read-back imports into (LinkedLists, PagedLists).
struct VulkanNodeListKind {
  Technique technique;
  std::unique_ptr<FragmentBuffer> (*import)(const TechniqueConfig& config, std::span<const std::uint32_t> heads,
                                            std::span<const glm::uvec2> entries, std::span<const std::uint32_t> links,
                                            std::uint64_t requested);
};

/// One pool of fixed size on a device (lossless growth makes a larger one).
class VulkanLinkedLists final : public VulkanTechnique {
 public:
  /// Throws std::invalid_argument for a configuration the CPU would refuse
  /// (an automatic pool of 0 included: the build sizes it first),
  /// VulkanError for a mode the device cannot run or a pool beyond its
  /// storage range. Lists or sorted-lists, by the configuration's technique.
  VulkanLinkedLists(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode);
  /// The same for `kind`'s technique (paged lists: techniques/paged_lists/vk).
  VulkanLinkedLists(const VulkanContext& context, const TechniqueConfig& config, const VulkanNodeListKind& kind,
                    AtomicMode mode);

  void write_params(ParamBlock& p) const override;
  [[nodiscard]] std::vector<BoundBuffer> buffers() const override;
  void record_clear(VkCommandBuffer cmd) const override;
  void gathered(std::span<const std::uint32_t> counter_words) override;
  [[nodiscard]] std::uint64_t capacity() const override { return config_.pool_capacity; }
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  VulkanNodeListKind kind_;
  VulkanBuffer heads_, nodes_, links_, saturation_;
  std::uint64_t requested_ = 0;  ///< nodes the last gather asked for (the counter)
};

}  // namespace habuffer::vk
