/// @file
/// A storage buffer in device memory (device-local where the device has
/// such memory), filled and read through a host-visible staging copy.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/vk/vulkan_context.h"

namespace habuffer::vk {

/// A storage buffer of a context's device; movable, not copyable.
class VulkanBuffer {
 public:
  VulkanBuffer() = default;
  /// `bytes` (at least 4; rounded up to 4) of device memory, zeroed; `usage` adds to
  /// storage, transfer source and destination. Throws VulkanError naming the
  /// size when the device has no memory for it or it exceeds
  /// maxStorageBufferRange.
  VulkanBuffer(const VulkanContext& context, std::uint64_t bytes, VkBufferUsageFlags usage = 0);
  ~VulkanBuffer();
  VulkanBuffer(VulkanBuffer&& other) noexcept;
  VulkanBuffer& operator=(VulkanBuffer&& other) noexcept;
  VulkanBuffer(const VulkanBuffer&) = delete;
  VulkanBuffer& operator=(const VulkanBuffer&) = delete;

  [[nodiscard]] VkBuffer handle() const { return buffer_; }
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

  /// Writes `data` at offset 0 (waits for the copy).
  void upload(const void* data, std::uint64_t bytes);
  template <typename T>
  void upload(std::span<const T> values) {
    upload(values.data(), values.size_bytes());
  }
  /// The first `bytes` (waits for every command before: call between submissions).
  [[nodiscard]] std::vector<std::uint8_t> read_bytes(std::uint64_t bytes) const;
  template <typename T>
  [[nodiscard]] std::vector<T> read(std::uint64_t count) const {
    const std::vector<std::uint8_t> raw = read_bytes(count * sizeof(T));
    std::vector<T> out(count);
    if (count > 0) std::memcpy(out.data(), raw.data(), raw.size());
    return out;
  }
  /// Records a fill of the whole buffer with zeros.
  void record_zero(VkCommandBuffer cmd) const;

 private:
  void release();
  const VulkanContext* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  std::uint64_t bytes_ = 0;
};

/// A host-visible, coherent buffer, mapped for its whole life: what the
/// device copies into for the host to read without a wait (a frame's
/// counters, read once its event is set). Movable, not copyable.
class MappedBuffer {
 public:
  MappedBuffer() = default;
  /// `bytes` (at least 4) with `usage` (transfer destination and source
  /// added). Throws VulkanError naming the size when the device has no
  /// memory for it.
  MappedBuffer(const VulkanContext& context, std::uint64_t bytes, VkBufferUsageFlags usage = 0);
  ~MappedBuffer();
  MappedBuffer(MappedBuffer&& other) noexcept;
  MappedBuffer& operator=(MappedBuffer&& other) noexcept;
  MappedBuffer(const MappedBuffer&) = delete;
  MappedBuffer& operator=(const MappedBuffer&) = delete;

  [[nodiscard]] VkBuffer handle() const { return buffer_; }
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }
  /// The mapped memory (coherent: the device's writes before a host
  /// barrier and a completed signal are seen here).
  [[nodiscard]] void* data() const { return mapped_; }

 private:
  void release();
  const VulkanContext* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  std::uint64_t bytes_ = 0;
};

/// Records a barrier after which every shader and transfer read and write
/// sees every earlier one (compute and transfer; the library's passes).
void record_full_barrier(VkCommandBuffer cmd);

}  // namespace habuffer::vk
