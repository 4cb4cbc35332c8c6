#include "habuffer/vk/techniques/ha/vulkan_ha_table.h"

#include <algorithm>

#include "habuffer/shared/ha_constants.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/techniques/ha/ha_param_block.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_glsl.h"

namespace habuffer::vk {
namespace {

TechniqueConfig with_table(TechniqueConfig c) {
  c.buffer.validate();
  c.buffer.table = c.buffer.table_or_screen();
  return c;
}

}  // namespace

VulkanHaTable::VulkanHaTable(const VulkanContext& context, const TechniqueConfig& config, const OffsetSource& offsets,
                             AtomicMode mode)
    : VulkanTechnique(context, with_table(config), mode),
      buffer_(config_.buffer),
      offsets_(offsets.make(buffer_.table, buffer_.record_layout().max_age())) {
  if (config.technique != Technique::Ha)
    throw std::invalid_argument("VulkanHaTable holds an HA-buffer, not " + to_string(config.technique));
  check_atomic_mode(context, mode, buffer_.layout);
  const std::uint64_t slots = buffer_.table.area();
  if (slots > UINT32_MAX)
    throw VulkanError("the Vulkan path indexes at most 2^32 - 1 slots, table " + buffer_.table.str());
  const std::uint64_t cells = ha_max_age_cells(buffer_);
  if (cells > UINT32_MAX) throw VulkanError("max-age table of " + std::to_string(cells) + " cells is too large");
  cells_ = static_cast<std::uint32_t>(cells);
  table_ = VulkanBuffer(context, slots * buffer_.record_layout().word_bytes());
  max_age_ = VulkanBuffer(context, std::uint64_t{cells_} * 4);
  offset_values_ = VulkanBuffer(context, offsets_.size() * sizeof(glm::uvec2));
  offset_values_.upload(offsets_.values().data(), offsets_.size() * sizeof(glm::uvec2));
  locks_ = VulkanBuffer(context, emulated64_lock_bytes(mode, slots));
  saturation_ = VulkanBuffer(context, buffer_.saturation ? buffer_.screen.area() * 4 : 4);
}

void VulkanHaTable::write_params(ParamBlock& p) const { write_ha_params(buffer_, p); }

std::vector<BoundBuffer> VulkanHaTable::buffers() const {
  const gl::GlBindings b = vulkan_bindings();
  return {{b.table, &table_},
          {b.max_age, &max_age_},
          {b.offsets, &offset_values_},
          {b.locks, &locks_},
          {b.saturation, &saturation_}};
}

void VulkanHaTable::record_clear(VkCommandBuffer cmd) const {
  for (const VulkanBuffer* b : {&table_, &max_age_, &locks_, &saturation_}) b->record_zero(cmd);
}

std::uint64_t VulkanHaTable::capacity() const { return buffer_.table.area(); }

std::unique_ptr<FragmentBuffer> VulkanHaTable::read_back() const {
  const std::uint64_t slots = buffer_.table.area();
  std::vector<std::uint64_t> words(slots);
  if (buffer_.record_layout().word_bytes() == 8) {
    words = table_.read<std::uint64_t>(slots);
  } else {
    const std::vector<std::uint32_t> narrow = table_.read<std::uint32_t>(slots);
    std::copy(narrow.begin(), narrow.end(), words.begin());
  }
  auto buffer = std::make_unique<HaBuffer>(buffer_, offsets_);
  buffer->import_state(words, max_age_.read<std::uint32_t>(cells_));
  return buffer;
}

}  // namespace habuffer::vk
