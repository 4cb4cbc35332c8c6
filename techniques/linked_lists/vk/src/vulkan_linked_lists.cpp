#include "habuffer/vk/techniques/linked_lists/vulkan_linked_lists.h"

#include <stdexcept>

#include "habuffer/shared/ha_constants.h"
#include "habuffer/techniques/linked_lists/import_node_lists.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_glsl.h"

namespace habuffer::vk {
namespace {

constexpr VulkanNodeListKind kListsKind{Technique::Lists, import_node_lists<LinkedLists>};
constexpr VulkanNodeListKind kSortedListsKind{Technique::SortedLists, import_node_lists<LinkedLists>};

TechniqueConfig checked(const TechniqueConfig& c, const VulkanNodeListKind& kind) {
  if (c.technique != kind.technique)
    throw std::invalid_argument("this Vulkan node-list container holds " + to_string(kind.technique) + ", not " +
                                to_string(c.technique));
  c.validate();
  return c;
}

}  // namespace

VulkanLinkedLists::VulkanLinkedLists(const VulkanContext& context, const TechniqueConfig& config, AtomicMode mode)
    : VulkanLinkedLists(context, config, config.technique == Technique::SortedLists ? kSortedListsKind : kListsKind,
                        mode) {}

VulkanLinkedLists::VulkanLinkedLists(const VulkanContext& context, const TechniqueConfig& config,
                                     const VulkanNodeListKind& kind, AtomicMode mode)
    : VulkanTechnique(context, checked(config, kind), mode), kind_(kind) {
  check_atomic_mode(context, mode, config_.buffer.layout);
  const std::uint64_t pixels = config_.buffer.screen.area();
  heads_ = VulkanBuffer(context, pixels * 4);
  nodes_ = VulkanBuffer(context, config_.pool_capacity * sizeof(glm::uvec2));
  links_ = VulkanBuffer(context, config_.pool_capacity * 4);
  saturation_ = VulkanBuffer(context, config_.buffer.saturation ? pixels * 4 : 4);
}

void VulkanLinkedLists::write_params(ParamBlock& p) const { write_technique_params(config_, p); }

std::vector<BoundBuffer> VulkanLinkedLists::buffers() const {
  const gl::GlBindings b = vulkan_bindings();
  return {{b.heads, &heads_}, {b.nodes, &nodes_}, {b.links, &links_}, {b.saturation, &saturation_}};
}

void VulkanLinkedLists::record_clear(VkCommandBuffer cmd) const {
  // The node counter is zeroed with the frame's tallies; nodes and links are
  // written before they are read.
  heads_.record_zero(cmd);
  saturation_.record_zero(cmd);
}

void VulkanLinkedLists::gathered(std::span<const std::uint32_t> counter_words) {
  // Every node asked for, dropped ones included: what lossless growth sizes the pool by.
  requested_ = counter_words[HABUFFER_COUNTER_NODES];
}

std::unique_ptr<FragmentBuffer> VulkanLinkedLists::read_back() const {
  const std::uint64_t pixels = config_.buffer.screen.area();
  return kind_.import(config_, heads_.read<std::uint32_t>(pixels), nodes_.read<glm::uvec2>(config_.pool_capacity),
                      links_.read<std::uint32_t>(config_.pool_capacity), requested_);
}

}  // namespace habuffer::vk
