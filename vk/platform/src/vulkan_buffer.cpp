#include "habuffer/vk/vulkan_buffer.h"

#include <algorithm>
#include <utility>

#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {
namespace {

// A memory type of `bits` with all of `want`, else one with all of `fallback`.
std::uint32_t memory_type(VkPhysicalDevice device, std::uint32_t bits, VkMemoryPropertyFlags want,
                          VkMemoryPropertyFlags fallback) {
  VkPhysicalDeviceMemoryProperties props{};
  vkGetPhysicalDeviceMemoryProperties(device, &props);
  for (VkMemoryPropertyFlags flags : {want, fallback})
    for (std::uint32_t t = 0; t < props.memoryTypeCount; ++t)
      if ((bits & (1u << t)) != 0 && (props.memoryTypes[t].propertyFlags & flags) == flags) return t;
  throw VulkanError("no Vulkan memory type for a buffer");
}

// A buffer and its memory, bound; `host` memory is mapped by the caller.
void make_buffer(const VulkanContext& c, std::uint64_t bytes, VkBufferUsageFlags usage, bool host, VkBuffer& buffer,
                 VkDeviceMemory& memory) {
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = usage;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(c.device(), &bi, nullptr, &buffer), ("creating a buffer of " + std::to_string(bytes) + " bytes").c_str());
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(c.device(), buffer, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  const VkMemoryPropertyFlags host_flags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  ai.memoryTypeIndex = host ? memory_type(c.physical_device(), req.memoryTypeBits, host_flags, host_flags)
                            : memory_type(c.physical_device(), req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  const VkResult r = vkAllocateMemory(c.device(), &ai, nullptr, &memory);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(c.device(), buffer, nullptr);
    buffer = VK_NULL_HANDLE;
    throw VulkanError("allocating " + std::to_string(bytes) + " bytes on " + c.info().name + ": " + result_name(r));
  }
  if (const VkResult bound = vkBindBufferMemory(c.device(), buffer, memory, 0); bound != VK_SUCCESS) {
    vkFreeMemory(c.device(), memory, nullptr);
    vkDestroyBuffer(c.device(), buffer, nullptr);
    memory = VK_NULL_HANDLE;
    buffer = VK_NULL_HANDLE;
    throw VulkanError("binding " + std::to_string(bytes) + " bytes of memory to a buffer: " + result_name(bound));
  }
}

}  // namespace

VulkanBuffer::VulkanBuffer(const VulkanContext& context, std::uint64_t bytes, VkBufferUsageFlags usage)
    : context_(&context), bytes_(std::max<std::uint64_t>(4, (bytes + 3) / 4 * 4)) {
  if (bytes_ > context.info().max_storage_range)
    throw VulkanError("a buffer of " + std::to_string(bytes) + " bytes exceeds " + context.info().name + "'s " +
                      std::to_string(context.info().max_storage_range) + " per storage binding");
  make_buffer(context, bytes_,
              usage | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                  VK_BUFFER_USAGE_TRANSFER_DST_BIT,
              false, buffer_, memory_);
  // Zeroed, as the GL path's buffers are: a container's never-written words
  // (the pool's nodes beyond the ones used) read back as zero, not as what
  // the memory held before.
  try {
    context.submit_and_wait([&](VkCommandBuffer cmd) { record_zero(cmd); }, "zeroing a new buffer");
  } catch (...) {
    release();  // the destructor does not run for a constructor that throws
    throw;
  }
}

VulkanBuffer::~VulkanBuffer() { release(); }

VulkanBuffer::VulkanBuffer(VulkanBuffer&& other) noexcept
    : context_(other.context_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      bytes_(std::exchange(other.bytes_, 0)) {}

VulkanBuffer& VulkanBuffer::operator=(VulkanBuffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = other.context_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void VulkanBuffer::release() {
  if (context_ == nullptr) return;
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(context_->device(), buffer_, nullptr);
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(context_->device(), memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

void VulkanBuffer::upload(const void* data, std::uint64_t bytes) {
  if (bytes == 0) return;
  if (bytes > bytes_)
    throw VulkanError("uploading " + std::to_string(bytes) + " bytes into a buffer of " + std::to_string(bytes_));
  const MappedBuffer staging(*context_, bytes);
  std::memcpy(staging.data(), data, bytes);
  context_->submit_and_wait(
      [&](VkCommandBuffer cmd) {
        record_full_barrier(cmd);  // after the buffer's earlier writes (its zeroing, a gather)
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
      },
      "uploading a buffer");
}

std::vector<std::uint8_t> VulkanBuffer::read_bytes(std::uint64_t bytes) const {
  std::vector<std::uint8_t> out(bytes);
  if (bytes == 0) return out;
  if (bytes > bytes_)
    throw VulkanError("reading " + std::to_string(bytes) + " bytes from a buffer of " + std::to_string(bytes_));
  const MappedBuffer staging(*context_, bytes);
  context_->submit_and_wait(
      [&](VkCommandBuffer cmd) {
        record_full_barrier(cmd);
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
        // The copy's writes made visible to the host's read after the fence.
        VkMemoryBarrier to_host{};
        to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr,
                             0, nullptr);
      },
      "reading a buffer back");
  std::memcpy(out.data(), staging.data(), bytes);
  return out;
}

MappedBuffer::MappedBuffer(const VulkanContext& context, std::uint64_t bytes, VkBufferUsageFlags usage)
    : context_(&context), bytes_(std::max<std::uint64_t>(4, bytes)) {
  make_buffer(context, bytes_, usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
              buffer_, memory_);
  if (const VkResult r = vkMapMemory(context.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_); r != VK_SUCCESS) {
    release();
    throw VulkanError("mapping a host-visible buffer of " + std::to_string(bytes_) + " bytes: " + result_name(r));
  }
}

MappedBuffer::~MappedBuffer() { release(); }

MappedBuffer::MappedBuffer(MappedBuffer&& other) noexcept
    : context_(other.context_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      bytes_(std::exchange(other.bytes_, 0)) {}

MappedBuffer& MappedBuffer::operator=(MappedBuffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = other.context_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    mapped_ = std::exchange(other.mapped_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void MappedBuffer::release() {
  if (context_ == nullptr) return;
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(context_->device(), memory_, nullptr);  // unmaps it too
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(context_->device(), buffer_, nullptr);
  memory_ = VK_NULL_HANDLE;
  buffer_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

void VulkanBuffer::record_zero(VkCommandBuffer cmd) const { vkCmdFillBuffer(cmd, buffer_, 0, VK_WHOLE_SIZE, 0u); }

void record_full_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  const VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  vkCmdPipelineBarrier(cmd, stages, stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace habuffer::vk
