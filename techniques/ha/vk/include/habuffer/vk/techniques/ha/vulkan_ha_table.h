/// @file
/// The HA-buffer on a Vulkan device: the table of records (L64 or L32), the
/// max-age table, the probe offsets, emulated64's locks and the saturation
/// image, read back into the CPU's HaBuffer of the same configuration.
#pragma once

#include <memory>

#include "habuffer/offset_source.h"
#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// One HA-buffer of a fixed table on a device.
class VulkanHaTable final : public VulkanTechnique {
 public:
  /// Throws std::invalid_argument for a configuration the CPU would refuse
  /// (BufferConfig::validate), VulkanError for a mode the device cannot run
  /// or a table beyond its storage range (naming the sizes).
  VulkanHaTable(const VulkanContext& context, const TechniqueConfig& config, const OffsetSource& offsets,
                AtomicMode mode);

  [[nodiscard]] bool defers_calls() const override { return mode_ == AtomicMode::Emulated64; }
  void write_params(ParamBlock& p) const override;
  [[nodiscard]] std::vector<BoundBuffer> buffers() const override;
  void record_clear(VkCommandBuffer cmd) const override;
  [[nodiscard]] std::uint64_t capacity() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  BufferConfig buffer_;
  OffsetSequence offsets_;
  std::uint32_t cells_ = 0;  ///< max-age cells
  VulkanBuffer table_, max_age_, offset_values_, locks_, saturation_;
};

}  // namespace habuffer::vk
