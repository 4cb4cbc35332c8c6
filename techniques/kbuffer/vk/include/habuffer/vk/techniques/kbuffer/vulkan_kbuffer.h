/// @file
/// The k-buffer on a Vulkan device: its K layers of slots per pixel (L64 or
/// L32 records, kept sorted by the insertion; emulated64's locks), and with the occupancy map
/// its map and per-pixel limits, found by the count pass between the fill
/// gather and the insert gather; read back into the CPU's KBuffer.
#pragma once

#include <memory>

#include "habuffer/vk/compute_pipeline.h"
#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// One k-buffer of fixed layers on a device (lossless growth makes a new one).
class VulkanKBuffer final : public VulkanTechnique {
 public:
  /// Throws std::invalid_argument for a configuration the CPU would refuse,
  /// VulkanError for a mode the device cannot run or layers beyond its
  /// storage range (naming the sizes).
  VulkanKBuffer(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode);

  [[nodiscard]] bool defers_calls() const override { return mode_ == AtomicMode::Emulated64; }
  void write_params(ParamBlock& p) const override;
  [[nodiscard]] std::vector<BoundBuffer> buffers() const override;
  void record_clear(VkCommandBuffer cmd) const override;
  [[nodiscard]] bool fills_before_insert() const override { return config_.occupancy; }
  /// The count pass (kb_count.comp.glsl, the GL part's text).
  [[nodiscard]] std::string fill_pass_compute(std::string_view defines) const override;
  [[nodiscard]] std::uint64_t capacity() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  VulkanBuffer slots_, locks_, occupancy_, limits_, saturation_;
};

}  // namespace habuffer::vk
