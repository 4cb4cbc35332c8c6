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

/// The descriptor sets a pipeline's layout declares beyond set 0's buffers.
struct PipelineSets {
  /// The stages that see set 0: a frame driver's set, which a host's gather
  /// binds too, is declared for fragment shaders as well (a set binds only
  /// to layouts of the same declaration).
  VkShaderStageFlags frame_set_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  /// Set 1: one storage image at binding 0 (the resolve into a host's image).
  bool target_image = false;
};

/// Set 0's layout: the parameter block at binding 0 (a uniform buffer),
/// storage buffers at 1 to ComputePipeline::kStorageBindings, seen by
/// `stages` and compute. The caller destroys it. VulkanError naming `what`.
VkDescriptorSetLayout make_frame_set_layout(const VulkanContext& context, VkShaderStageFlags stages,
                                           const std::string& what);
/// Writes `buffers` into `set` (of make_frame_set_layout's declaration):
/// every binding, each checked bound (a VulkanError naming `what` and the
/// binding left unbound or not a buffer of the layout).
void write_frame_set(const VulkanContext& context, VkDescriptorSet set, std::span<const BoundBuffer> buffers,
                     const std::string& what);

/// One compiled compute shader and its layout; not copyable.
class ComputePipeline {
 public:
  /// Storage-buffer bindings 1..kStorageBindings (vulkan_bindings(): each
  /// technique's own three, then the six shared ones).
  static constexpr unsigned kStorageBindings = 9;
  /// Threads of a work group in x (local_size_x of the library's entries).
  static constexpr std::uint32_t kGroupSize = 64;

  /// Throws VulkanError naming `name` when the device refuses the module.
  ComputePipeline(const VulkanContext& context, std::span<const std::uint32_t> spirv, std::string name,
                  const PipelineSets& sets = {});
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  /// Set 0's layout (the parameter block and the storage buffers), for
  /// sets a caller allocates and keeps (a frame driver's, per container).
  [[nodiscard]] VkDescriptorSetLayout set_layout() const { return set_layout_; }
  /// Set 1's layout where PipelineSets::target_image, else VK_NULL_HANDLE.
  [[nodiscard]] VkDescriptorSetLayout image_set_layout() const { return image_set_layout_; }
  /// Records a dispatch over a screen (8x8 groups) with sets a caller
  /// allocated and wrote (set 0, then set 1 where the layout has it).
  void record_screen_with(VkCommandBuffer cmd, std::span<const VkDescriptorSet> sets, Extent screen) const;

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
  VkDescriptorSetLayout image_set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorPool> pools_;
  std::size_t pool_in_use_ = 0;
};

}  // namespace habuffer::vk
