#include "habuffer/vk/techniques/kbuffer/vulkan_kbuffer.h"

#include <stdexcept>
#include <string>

#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_glsl.h"
#include "kbuffer_glsl.h"

namespace habuffer::vk {
namespace {

TechniqueConfig checked(const TechniqueConfig& c) {
  if (c.technique != Technique::KBuffer)
    throw std::invalid_argument("VulkanKBuffer holds a k-buffer, not " + to_string(c.technique));
  c.validate();
  return c;
}

// A buffer of `bytes` for `what`, within one storage binding of the device.
VulkanBuffer sized(const VulkanContext& context, std::uint64_t bytes, const std::string& what) {
  if (bytes > context.info().max_storage_range)
    throw VulkanError(what + " needs " + std::to_string(bytes) + " bytes, beyond one storage binding of " +
                      context.info().name + " (" + std::to_string(context.info().max_storage_range) + " bytes)");
  return VulkanBuffer(context, bytes);
}

}  // namespace

VulkanKBuffer::VulkanKBuffer(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode)
    : VulkanTechnique(context, checked(config), mode) {
  check_atomic_mode(context, mode, config_.buffer.layout);
  const std::uint64_t pixels = config_.buffer.screen.area();
  slots_ = sized(context, capacity() * config_.buffer.record_layout().word_bytes(),
                 std::to_string(config_.layers) + " k-buffer layers of screen " + config_.buffer.screen.str());
  locks_ = VulkanBuffer(context, emulated64_lock_bytes(mode, capacity()));
  saturation_ = VulkanBuffer(context, config_.buffer.saturation ? pixels * 4 : 4);
  if (config_.occupancy) {
    occupancy_ = sized(context, pixels * config_.occupancy_words * 4,
                       "an occupancy map of " + std::to_string(config_.occupancy_words) + " words per pixel");
    limits_ = VulkanBuffer(context, pixels * 4);
  }
}

void VulkanKBuffer::write_params(ParamBlock& p) const { write_technique_params(config_, p); }

std::vector<BoundBuffer> VulkanKBuffer::buffers() const {
  const gl::GlBindings b = vulkan_bindings();
  std::vector<BoundBuffer> out{{b.slots, &slots_}, {b.locks, &locks_}, {b.saturation, &saturation_}};
  if (config_.occupancy) {
    out.push_back({b.occupancy, &occupancy_});
    out.push_back({b.limits, &limits_});
  }
  return out;
}

void VulkanKBuffer::record_clear(VkCommandBuffer cmd) const {
  // The limits are written by the count pass before the insert gather reads them.
  slots_.record_zero(cmd);
  locks_.record_zero(cmd);  // every critical section leaves its lock at 0 again; zeroed for a fresh container
  saturation_.record_zero(cmd);
  if (config_.occupancy) occupancy_.record_zero(cmd);
}

std::string VulkanKBuffer::fill_pass_compute(std::string_view defines) const {
  return vulkan_technique_module(Technique::KBuffer, mode_, gl::ShaderStage::Compute, defines) +
         gl::kKBufferCountCompute;
}

std::uint64_t VulkanKBuffer::capacity() const { return std::uint64_t{config_.layers} * config_.buffer.screen.area(); }

std::unique_ptr<FragmentBuffer> VulkanKBuffer::read_back() const {
  auto kb = std::make_unique<KBuffer>(config_);
  const std::vector<std::uint32_t> words =
      slots_.read<std::uint32_t>(capacity() * config_.buffer.record_layout().word_bytes() / 4);
  const std::vector<std::uint32_t> limits =
      config_.occupancy ? limits_.read<std::uint32_t>(config_.buffer.screen.area()) : std::vector<std::uint32_t>{};
  kb->import_state(words, limits);
  return kb;
}

}  // namespace habuffer::vk
