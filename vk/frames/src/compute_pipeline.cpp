#include "habuffer/vk/compute_pipeline.h"

#include <algorithm>
#include <array>
#include <utility>

#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {
namespace {

constexpr unsigned kBindings = ComputePipeline::kStorageBindings + 1;
constexpr std::uint32_t kSetsPerPool = 64;

}  // namespace

VkDescriptorSetLayout make_frame_set_layout(const VulkanContext& context, VkShaderStageFlags stages,
                                           const std::string& what) {
  std::array<VkDescriptorSetLayoutBinding, kBindings> bindings{};
  for (unsigned b = 0; b < kBindings; ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType = b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = stages | VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  li.bindingCount = kBindings;
  li.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  check(vkCreateDescriptorSetLayout(context.device(), &li, nullptr, &layout), (what + ": the descriptor set layout").c_str());
  return layout;
}

void write_frame_set(const VulkanContext& context, VkDescriptorSet set, std::span<const BoundBuffer> buffers,
                     const std::string& what) {
  std::array<const VulkanBuffer*, kBindings> at{};
  for (const BoundBuffer& b : buffers) {
    if (b.binding >= kBindings || b.buffer == nullptr || !*b.buffer)
      throw VulkanError(what + ": binding " + std::to_string(b.binding) + " is not a buffer of its layout");
    at[b.binding] = b.buffer;
  }
  for (unsigned b = 0; b < kBindings; ++b)
    if (at[b] == nullptr) throw VulkanError(what + ": binding " + std::to_string(b) + " left unbound");
  std::array<VkDescriptorBufferInfo, kBindings> infos{};
  std::array<VkWriteDescriptorSet, kBindings> writes{};
  for (unsigned b = 0; b < kBindings; ++b) {
    infos[b] = {at[b]->handle(), 0, VK_WHOLE_SIZE};
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(context.device(), kBindings, writes.data(), 0, nullptr);
}


ComputePipeline::ComputePipeline(const VulkanContext& context, std::span<const std::uint32_t> spirv, std::string name,
                                 const PipelineSets& sets)
    : context_(context), name_(std::move(name)) {
  const VkDevice device = context.device();
  // Everything made so far goes with a throw (the destructor does not run).
  struct Undo {
    ComputePipeline* p;
    bool armed = true;
    ~Undo() {
      if (!armed) return;
      const VkDevice d = p->context_.device();
      if (p->pipeline_) vkDestroyPipeline(d, p->pipeline_, nullptr);
      if (p->layout_) vkDestroyPipelineLayout(d, p->layout_, nullptr);
      if (p->set_layout_) vkDestroyDescriptorSetLayout(d, p->set_layout_, nullptr);
      if (p->image_set_layout_) vkDestroyDescriptorSetLayout(d, p->image_set_layout_, nullptr);
      if (p->module_) vkDestroyShaderModule(d, p->module_, nullptr);
    }
  } undo{this};
  VkShaderModuleCreateInfo mi{};
  mi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  mi.codeSize = spirv.size_bytes();
  mi.pCode = spirv.data();
  check(vkCreateShaderModule(device, &mi, nullptr, &module_), (name_ + ": the shader module").c_str());
  set_layout_ = make_frame_set_layout(context, sets.frame_set_stages, name_);
  std::array<VkDescriptorSetLayout, 2> set_layouts{set_layout_, VK_NULL_HANDLE};
  if (sets.target_image) {
    VkDescriptorSetLayoutBinding image{};
    image.binding = 0;
    image.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    image.descriptorCount = 1;
    image.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    VkDescriptorSetLayoutCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    ii.bindingCount = 1;
    ii.pBindings = &image;
    check(vkCreateDescriptorSetLayout(device, &ii, nullptr, &image_set_layout_),
          (name_ + ": the image's descriptor set layout").c_str());
    set_layouts[1] = image_set_layout_;
  }
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(std::uint32_t)};
  VkPipelineLayoutCreateInfo pli{};
  pli.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pli.setLayoutCount = sets.target_image ? 2 : 1;
  pli.pSetLayouts = set_layouts.data();
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(device, &pli, nullptr, &layout_), (name_ + ": the pipeline layout").c_str());
  VkComputePipelineCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module_;
  ci.stage.pName = "main";
  ci.layout = layout_;
  check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_), (name_ + ": the pipeline").c_str());
  context.check_messages(name_.c_str());
  undo.armed = false;
}

ComputePipeline::~ComputePipeline() {
  const VkDevice d = context_.device();
  for (VkDescriptorPool p : pools_) vkDestroyDescriptorPool(d, p, nullptr);
  vkDestroyPipeline(d, pipeline_, nullptr);
  vkDestroyPipelineLayout(d, layout_, nullptr);
  vkDestroyDescriptorSetLayout(d, set_layout_, nullptr);
  if (image_set_layout_) vkDestroyDescriptorSetLayout(d, image_set_layout_, nullptr);
  vkDestroyShaderModule(d, module_, nullptr);
}

void ComputePipeline::begin_recording() {
  for (VkDescriptorPool p : pools_) vkResetDescriptorPool(context_.device(), p, 0);
  pool_in_use_ = 0;
}

VkDescriptorSet ComputePipeline::allocate_set() {
  for (;;) {
    if (pool_in_use_ == pools_.size()) {
      const std::array<VkDescriptorPoolSize, 2> sizes{{{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSetsPerPool},
                                                       {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSetsPerPool * (kBindings - 1)}}};
      VkDescriptorPoolCreateInfo pi{};
      pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
      pi.maxSets = kSetsPerPool;
      pi.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
      pi.pPoolSizes = sizes.data();
      VkDescriptorPool pool = VK_NULL_HANDLE;
      check(vkCreateDescriptorPool(context_.device(), &pi, nullptr, &pool), (name_ + ": a descriptor pool").c_str());
      pools_.push_back(pool);
    }
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pools_[pool_in_use_];
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout_;
    VkDescriptorSet set = VK_NULL_HANDLE;
    const VkResult r = vkAllocateDescriptorSets(context_.device(), &ai, &set);
    if (r == VK_SUCCESS) return set;
    if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL)
      check(r, (name_ + ": a descriptor set").c_str());
    ++pool_in_use_;  // this pool is full: the next (made when there is none)
  }
}

void ComputePipeline::bind(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, std::uint32_t count) {
  if (image_set_layout_ != VK_NULL_HANDLE)
    throw VulkanError(name_ + ": a pipeline with an image set records with record_screen_with");
  const VkDescriptorSet set = allocate_set();
  write_frame_set(context_, set, buffers, name_);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof count, &count);
}

void ComputePipeline::record_screen(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, Extent screen) {
  bind(cmd, buffers, 0);
  vkCmdDispatch(cmd, (screen.x + 7) / 8, (screen.y + 7) / 8, 1);
}

void ComputePipeline::record_screen_with(VkCommandBuffer cmd, std::span<const VkDescriptorSet> sets,
                                         Extent screen) const {
  const std::size_t want = image_set_layout_ != VK_NULL_HANDLE ? 2 : 1;
  if (sets.size() != want)
    throw VulkanError(name_ + ": " + std::to_string(want) + " descriptor sets are bound, " +
                      std::to_string(sets.size()) + " given");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, static_cast<std::uint32_t>(sets.size()),
                          sets.data(), 0, nullptr);
  const std::uint32_t count = 0;
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof count, &count);
  vkCmdDispatch(cmd, (screen.x + 7) / 8, (screen.y + 7) / 8, 1);
}

void ComputePipeline::record(VkCommandBuffer cmd, std::span<const BoundBuffer> buffers, std::uint32_t count,
                             std::uint64_t invocations) {
  bind(cmd, buffers, count);
  // A 2D grid of groups, as the GL path's (compute_grid.h): x within the
  // device's limit, the rows above it.
  const std::uint64_t groups = (invocations + kGroupSize - 1) / kGroupSize;
  if (groups == 0) return;
  const std::uint64_t x_limit = std::min<std::uint64_t>(context_.info().max_work_groups_x, 65535);
  const std::uint64_t x = std::min(groups, x_limit);
  const std::uint64_t y = (groups + x - 1) / x;
  if (y > context_.info().max_work_groups_y)
    throw VulkanError(name_ + ": " + std::to_string(invocations) + " invocations exceed " + context_.info().name +
                      "'s grid of work groups");
  vkCmdDispatch(cmd, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), 1);
}

}  // namespace habuffer::vk
