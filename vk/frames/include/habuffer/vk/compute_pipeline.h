/// @file
/// A compute pipeline of the Vulkan path: one SPIR-V module, one descriptor
/// set (set 0) laid out as vulkan_bindings() is (the parameter block at 0, a
/// storage buffer at each of 1 to kStorageBindings), a 4-byte push constant
/// (the count an entry reads), and the descriptor sets its recorded
/// dispatches use.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/extent.h"
#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_context.h"

namespace habuffer::vk {

/// A buffer at a binding point of set 0.
struct BoundBuffer {
  unsigned binding = 0;
  const VulkanBuffer* buffer = nullptr;
};

/// One compiled compute shader and its layout; not copyable.
class ComputePipeline {
 public:
  /// Storage-buffer bindings 1..kStorageBindings (vulkan_bindings(): each
  /// technique's own three, then the six shared ones).
  static constexpr unsigned kStorageBindings = 9;
  /// Threads of a work group in x (local_size_x of the library's entries).
  static constexpr std::uint32_t kGroupSize = 64;

  /// Throws VulkanError naming `name` when the device refuses the module.
  ComputePipeline(const VulkanContext& context, std::span<const std::uint32_t> spirv, std::string name);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  /// Frees the descriptor sets earlier recordings used (call when no
  /// submission that used them is pending).
  void begin_recording();
  /// Records a dispatch of `invocations` threads (a 2D grid of work groups
  /// within the device's limits) with `buffers` bound (every binding of the
  /// layout: the parameter block at 0, storage at 1..kStorageBindings) and
  /// `count` as the push constant. Throws VulkanError naming a binding left
  /// unbound.
  void record(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, std::uint32_t count,
              std::uint64_t invocations);
  /// The same over a screen, one invocation per pixel in 8x8 work groups
  /// (the sort pass's local size).
  void record_screen(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, Extent screen);

 private:
  VkDescriptorSet allocate_set();
  // Binds the pipeline, a set of `buffers` and the push constant.
  void bind(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, std::uint32_t count);
  const VulkanContext& context_;
  std::string name_;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorPool> pools_;
  std::size_t pool_in_use_ = 0;
};

}  // namespace habuffer::vk
