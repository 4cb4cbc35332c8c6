// The Vulkan frame driver (issue 48, item 3) inside a host's own command
// buffers: a host that draws fragments as points through its own render
// pass and pipeline, its fragment shader built from the driver's module,
// gives the CPU path's lists and counters for every technique the driver
// runs, in native64 and native32; the resolve into the host's image equals
// the CPU's composite float for float; an automatic table is counted at its
// first frame and follows jumps across frames (SPEC 8); misuse is refused
// in one line. The validation layer watches the device: a message fails
// the submission that caused it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/lossless_build.h"
#include "habuffer/vk.h"
#include "test_support.h"
#include "vk_test_support.h"

namespace habuffer {
namespace {

// The host's vertex shader: one point a fragment at its pixel's centre,
// passing the fragment on to the gather's fragment shader.
constexpr const char* kPointVertex = R"(#version 450
layout(location = 0) in uvec2 a_pixel;
layout(location = 1) in float a_depth;
layout(location = 2) in uint a_rgba;
layout(location = 3) in uint a_coverage;
layout(push_constant) uniform HostScreen { vec2 host_screen; };
layout(location = 0) flat out uvec2 v_pixel;
layout(location = 1) flat out float v_depth;
layout(location = 2) flat out uint v_rgba;
layout(location = 3) flat out uint v_coverage;
void main() {
  v_pixel = a_pixel;
  v_depth = a_depth;
  v_rgba = a_rgba;
  v_coverage = a_coverage;
  gl_Position = vec4((vec2(a_pixel) + 0.5) / host_screen * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
)";

// The host's gather fragment shader, after the driver's module.
constexpr const char* kPointFragment = R"(
layout(location = 0) flat in uvec2 v_pixel;
layout(location = 1) flat in float v_depth;
layout(location = 2) flat in uint v_rgba;
layout(location = 3) flat in uint v_coverage;
void main() { habuffer_insert(v_pixel, v_depth, v_coverage, v_rgba); }
)";

void check_vk(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw vk::VulkanError(std::string("test host: ") + what + ": " + vk::result_name(r));
}

// A host written as a renderer would be: its own render pass (no
// attachments: the gather writes only the driver's buffers), pipeline,
// vertex buffer, command buffers and fence, and a storage image it resolves into.
class PointHost {
 public:
  PointHost(const vk::VulkanContext& context, Extent screen) : c_(context), screen_(screen) {
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    VkRenderPassCreateInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    check_vk(vkCreateRenderPass(d(), &rp, nullptr, &render_pass_), "render pass");
    VkFramebufferCreateInfo fb{};
    fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fb.renderPass = render_pass_;
    fb.width = screen.x;
    fb.height = screen.y;
    fb.layers = 1;
    check_vk(vkCreateFramebuffer(d(), &fb, nullptr, &framebuffer_), "framebuffer");
    VkCommandPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = c_.queue_family();
    check_vk(vkCreateCommandPool(d(), &pool, nullptr, &pool_), "command pool");
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check_vk(vkCreateFence(d(), &fi, nullptr, &fence_), "fence");
  }
  ~PointHost() {
    vkDeviceWaitIdle(d());
    if (image_view_) vkDestroyImageView(d(), image_view_, nullptr);
    if (image_) vkDestroyImage(d(), image_, nullptr);
    if (image_memory_) vkFreeMemory(d(), image_memory_, nullptr);
    release_pipeline();
    vkDestroyFence(d(), fence_, nullptr);
    vkDestroyCommandPool(d(), pool_, nullptr);
    vkDestroyFramebuffer(d(), framebuffer_, nullptr);
    vkDestroyRenderPass(d(), render_pass_, nullptr);
  }
  PointHost(const PointHost&) = delete;
  PointHost& operator=(const PointHost&) = delete;

  // The gather pipeline for `driver`'s module (set 0 its set layout).
  void make_pipeline(const vk::VulkanFrameDriver& driver) {
    release_pipeline();
    const std::vector<std::uint32_t> vs = vk::compile_to_spirv(kPointVertex, vk::SpirvStage::Vertex, "point vertex");
    const std::vector<std::uint32_t> fs = driver.compile_gather_fragment(kPointFragment);
    const auto module = [&](const std::vector<std::uint32_t>& code) {
      VkShaderModuleCreateInfo mi{};
      mi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
      mi.codeSize = code.size() * 4;
      mi.pCode = code.data();
      VkShaderModule m = VK_NULL_HANDLE;
      check_vk(vkCreateShaderModule(d(), &mi, nullptr, &m), "shader module");
      return m;
    };
    vertex_ = module(vs);
    fragment_ = module(fs);
    const VkDescriptorSetLayout set = driver.set_layout();
    const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, 8};
    VkPipelineLayoutCreateInfo li{};
    li.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    li.setLayoutCount = 1;
    li.pSetLayouts = &set;
    li.pushConstantRangeCount = 1;
    li.pPushConstantRanges = &push;
    check_vk(vkCreatePipelineLayout(d(), &li, nullptr, &layout_), "pipeline layout");
    VkPipelineShaderStageCreateInfo stages[2]{};
    for (int i = 0; i < 2; ++i) {
      stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
      stages[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
      stages[i].module = i == 0 ? vertex_ : fragment_;
      stages[i].pName = "main";
    }
    const VkVertexInputBindingDescription binding{0, sizeof(Fragment), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[4] = {
        {0, 0, VK_FORMAT_R32G32_UINT, offsetof(Fragment, x)},
        {1, 0, VK_FORMAT_R32_SFLOAT, offsetof(Fragment, depth)},
        {2, 0, VK_FORMAT_R32_UINT, offsetof(Fragment, rgba)},
        {3, 0, VK_FORMAT_R32_UINT, offsetof(Fragment, coverage)}};
    VkPipelineVertexInputStateCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = 4;
    vi.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo ia{};
    ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    ia.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    const VkViewport viewport{0, 0, static_cast<float>(screen_.x), static_cast<float>(screen_.y), 0, 1};
    const VkRect2D scissor{{0, 0}, {screen_.x, screen_.y}};
    VkPipelineViewportStateCreateInfo vp{};
    vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    vp.viewportCount = 1;
    vp.pViewports = &viewport;
    vp.scissorCount = 1;
    vp.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo rs{};
    rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{};
    ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendStateCreateInfo cb{};
    cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    VkGraphicsPipelineCreateInfo pi{};
    pi.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    pi.stageCount = 2;
    pi.pStages = stages;
    pi.pVertexInputState = &vi;
    pi.pInputAssemblyState = &ia;
    pi.pViewportState = &vp;
    pi.pRasterizationState = &rs;
    pi.pMultisampleState = &ms;
    pi.pColorBlendState = &cb;
    pi.layout = layout_;
    pi.renderPass = render_pass_;
    check_vk(vkCreateGraphicsPipelines(d(), VK_NULL_HANDLE, 1, &pi, nullptr, &pipeline_), "gather pipeline");
  }

  // The fragments the next gathers draw (the buffers of earlier uploads are
  // kept: frames recorded with them may still be in flight).
  void upload(const std::vector<Fragment>& fragments) {
    vertices_.emplace_back(c_, std::max<std::size_t>(1, fragments.size()) * sizeof(Fragment),
                           VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    if (!fragments.empty()) std::memcpy(vertices_.back().data(), fragments.data(), fragments.size() * sizeof(Fragment));
    count_ = static_cast<std::uint32_t>(fragments.size());
  }

  // The gather record_frame calls: the host's render pass, its pipeline, the
  // driver's set, the fragments of the latest upload.
  vk::VulkanFrameDriver::Gather gather(vk::VulkanFrameDriver& driver, bool bind = true) {
    const VkBuffer vb = vertices_.back().handle();
    const std::uint32_t count = count_;
    return [this, &driver, bind, vb, count](VkCommandBuffer cmd) {
      VkRenderPassBeginInfo rb{};
      rb.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
      rb.renderPass = render_pass_;
      rb.framebuffer = framebuffer_;
      rb.renderArea = {{0, 0}, {screen_.x, screen_.y}};
      vkCmdBeginRenderPass(cmd, &rb, VK_SUBPASS_CONTENTS_INLINE);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
      if (bind) driver.bind(cmd, layout_);
      const float size[2] = {static_cast<float>(screen_.x), static_cast<float>(screen_.y)};
      vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof size, size);
      const VkDeviceSize offset = 0;
      vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
      if (count > 0) vkCmdDraw(cmd, count, 1, 0, 0);
      vkCmdEndRenderPass(cmd);
    };
  }

  // Records a command buffer, submits it and waits; the validation layer's
  // messages fail it (the context collects them).
  void submit(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBuffer cmd = begin();
    record(cmd);
    end_and_submit(cmd);
  }
  VkCommandBuffer begin() {
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check_vk(vkAllocateCommandBuffers(d(), &ai, &cmd), "command buffer");
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check_vk(vkBeginCommandBuffer(cmd, &bi), "begin");
    return cmd;
  }
  // Ends and submits command buffers in order, one submission, without a
  // wait (wait() waits and frees them).
  void submit_without_wait(std::vector<VkCommandBuffer> cmds) {
    for (VkCommandBuffer cmd : cmds) check_vk(vkEndCommandBuffer(cmd), "end");
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = static_cast<std::uint32_t>(cmds.size());
    si.pCommandBuffers = cmds.data();
    check_vk(vkQueueSubmit(c_.queue(), 1, &si, fence_), "submit");
    pending_ = std::move(cmds);
  }
  void wait() {
    check_vk(vkWaitForFences(d(), 1, &fence_, VK_TRUE, 60'000'000'000ull), "wait");
    check_vk(vkResetFences(d(), 1, &fence_), "reset fence");
    vkFreeCommandBuffers(d(), pool_, static_cast<std::uint32_t>(pending_.size()), pending_.data());
    pending_.clear();
    c_.check_messages("the test host's submission");
  }

  void end_and_submit(VkCommandBuffer cmd) {
    check_vk(vkEndCommandBuffer(cmd), "end");
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check_vk(vkQueueSubmit(c_.queue(), 1, &si, fence_), "submit");
    check_vk(vkWaitForFences(d(), 1, &fence_, VK_TRUE, 60'000'000'000ull), "wait");
    check_vk(vkResetFences(d(), 1, &fence_), "reset fence");
    vkFreeCommandBuffers(d(), pool_, 1, &cmd);
    c_.check_messages("the test host's submission");
  }

  // Ends a command buffer and frees it unsubmitted.
  void discard(VkCommandBuffer cmd) {
    check_vk(vkEndCommandBuffer(cmd), "end");
    vkFreeCommandBuffers(d(), pool_, 1, &cmd);
  }

  // An RGBA float storage image holding `backgrounds` (alpha `alpha`), in GENERAL.
  vk::HostImage image_with(const std::vector<glm::vec3>& backgrounds, float alpha) {
    if (!image_) make_image();
    std::vector<glm::vec4> texels(backgrounds.size());
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec4(backgrounds[i], alpha);
    const vk::MappedBuffer staging(c_, texels.size() * sizeof(glm::vec4));
    std::memcpy(staging.data(), texels.data(), texels.size() * sizeof(glm::vec4));
    submit([&](VkCommandBuffer cmd) {
      transition(cmd, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {screen_.x, screen_.y, 1}};
      vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    });
    return vk::HostImage{image_, image_view_, VK_FORMAT_R32G32B32A32_SFLOAT, screen_,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
  }
  std::vector<glm::vec4> read_image() {
    const vk::MappedBuffer staging(c_, screen_.area() * sizeof(glm::vec4));
    submit([&](VkCommandBuffer cmd) {
      const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {screen_.x, screen_.y, 1}};
      vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
      VkMemoryBarrier b{};
      b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
      b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0, nullptr, 0,
                           nullptr);
    });
    std::vector<glm::vec4> out(screen_.area());
    std::memcpy(out.data(), staging.data(), out.size() * sizeof(glm::vec4));
    return out;
  }

 private:
  VkDevice d() const { return c_.device(); }
  void release_pipeline() {
    if (pipeline_) vkDestroyPipeline(d(), pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(d(), layout_, nullptr);
    if (vertex_) vkDestroyShaderModule(d(), vertex_, nullptr);
    if (fragment_) vkDestroyShaderModule(d(), fragment_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    vertex_ = fragment_ = VK_NULL_HANDLE;
  }
  void make_image() {
    VkImageCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    ii.extent = {screen_.x, screen_.y, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check_vk(vkCreateImage(d(), &ii, nullptr, &image_), "image");
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(d(), image_, &req);
    VkPhysicalDeviceMemoryProperties props{};
    vkGetPhysicalDeviceMemoryProperties(c_.physical_device(), &props);
    std::uint32_t type = 0;
    while (type < props.memoryTypeCount && (req.memoryTypeBits & (1u << type)) == 0) ++type;
    VkMemoryAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    check_vk(vkAllocateMemory(d(), &ai, nullptr, &image_memory_), "image memory");
    check_vk(vkBindImageMemory(d(), image_, image_memory_, 0), "bind image memory");
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image_;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check_vk(vkCreateImageView(d(), &vi, nullptr, &image_view_), "image view");
  }
  void transition(VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image_;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &b);
  }

  const vk::VulkanContext& c_;
  Extent screen_;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkShaderModule vertex_ = VK_NULL_HANDLE, fragment_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::vector<vk::MappedBuffer> vertices_;
  std::uint32_t count_ = 0;
  std::vector<VkCommandBuffer> pending_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory image_memory_ = VK_NULL_HANDLE;
  VkImageView image_view_ = VK_NULL_HANDLE;
};

// The modes the frame driver runs on this device (not emulated64).
std::vector<AtomicMode> driver_modes() {
  std::vector<AtomicMode> out;
  for (AtomicMode m : vk::runnable_atomic_modes(context().info()))
    if (m != AtomicMode::Emulated64) out.push_back(m);
  return out;
}

// `c` with the HA-buffer's table a host would have for `fragments`: the
// policy's middle of the band (a table as full as the screen-sized default
// at thousands of fragments makes calls probe past a software device's loop
// budget, which ends them: counted, not stored).
TechniqueConfig sized_table(TechniqueConfig c, std::uint64_t fragments) {
  c.buffer.table = {};
  return c.sized_for(ResizePolicy{}, fragments);
}

// A frame of `fragments` recorded and submitted; its report.
vk::VulkanFrameReport one_frame(PointHost& host, vk::VulkanFrameDriver& driver, const std::vector<Fragment>& fragments) {
  host.upload(fragments);
  host.submit([&](VkCommandBuffer cmd) { driver.record_frame(cmd, host.gather(driver)); });
  std::vector<vk::VulkanFrameReport> reports = driver.finish_reports();
  if (reports.size() != 1) throw std::logic_error("one frame, " + std::to_string(reports.size()) + " reports");
  return reports.front();
}

// A frame of `fragments` resolved into `image` in one command buffer,
// submitted and waited for; the reports.
std::vector<vk::VulkanFrameReport> frame_and_resolve(PointHost& host, vk::VulkanFrameDriver& driver,
                                                     const std::vector<Fragment>& fragments, const vk::HostImage& image) {
  host.upload(fragments);
  host.submit([&](VkCommandBuffer cmd) {
    driver.record_frame(cmd, host.gather(driver));
    driver.record_resolve(cmd, image);
  });
  return driver.finish_reports();
}

TEST(VulkanHost, AHostsOwnRenderPassGivesTheCpuListsAndCountersForEveryTechniqueTheDriverRuns) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : driver_modes()) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    for (Technique t : {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::Arrays,
                        Technique::KBuffer, Technique::PagedLists})
      for (std::uint64_t seed = 1; seed <= 2; ++seed) {
        SCOPED_TRACE(to_string(mode) + " " + to_string(t) + " seed " + std::to_string(seed));
        const Extent screen{29 + 4 * static_cast<std::uint32_t>(seed), 17};
        const std::vector<Fragment> f =
            test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 2200 + 700 * seed, seed);
        TechniqueConfig c = test::technique_config(t, screen, layout);
        if (t == Technique::Ha) c = sized_table(c, f.size());
        if (uses_pool(t)) c.pool_capacity = f.size();
        // Room for pages the device's racing calls take and never link (none on the CPU).
        if (t == Technique::PagedLists) c.pool_capacity = 2 * f.size();
        if (t == Technique::KBuffer) {
          c.layers = 4;
          c.occupancy = seed == 2;
          c.occupancy_words = 2;
        }
        if (t == Technique::Arrays) c.layers = seed == 1 ? 3 : 16;  // K too small once: dropped alike
        vk::VulkanFrameDriver driver(context(), c, {});
        EXPECT_EQ(driver.mode(), mode);
        PointHost host(context(), screen);
        host.make_pipeline(driver);
        // Two frames of the same scene: the second clears the first's lists.
        for (int frame = 0; frame < 2; ++frame) {
          const vk::VulkanFrameReport r = one_frame(host, driver, f);
          const TechniqueBuild cpu = build_technique(r.config, {}, f, {}, {}, 1);
          EXPECT_EQ(r.index, static_cast<std::uint64_t>(frame));
          EXPECT_EQ(r.counters, cpu.counters);
          // Arrays keep a full pixel's first K arrivals, in the device's order.
          if (t != Technique::Arrays || cpu.counters.failures() == 0) {
            EXPECT_EQ(test::traversed_lists(*driver.read_back()), test::traversed_lists(*cpu.buffer));
          }
          EXPECT_EQ(r.ended_by_driver, 0u);
          if (context().info().timestamps) {
            EXPECT_GT(r.gather_ms, 0.0);
          }
        }
      }
  }
}

// The resolve into the host's image: each pixel's list over the image's
// texel, float for float the CPU's composite over the same backgrounds;
// alpha (1 - T) + T * the texel's.
TEST(VulkanHost, TheResolveIntoTheHostsImageIsTheCpuCompositeOverItBitForBit) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : driver_modes()) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    for (Technique t : {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::Arrays,
                        Technique::KBuffer, Technique::PagedLists}) {
      SCOPED_TRACE(to_string(mode) + " " + to_string(t));
      const Extent screen{37, 21};
      TechniqueConfig c = test::technique_config(t, screen, layout);
      if (t == Technique::KBuffer || t == Technique::Arrays) c.layers = 4;
      const std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 3000, 9);
      if (t == Technique::Ha) c = sized_table(c, f.size());
      std::vector<glm::vec3> backgrounds(screen.area());
      for (std::size_t i = 0; i < backgrounds.size(); ++i)
        backgrounds[i] = glm::vec3(static_cast<float>(i % 7) / 7.0f, 0.25f, static_cast<float>(i % 3) / 3.0f);
      vk::VulkanFrameDriver driver(context(), c, {});
      PointHost host(context(), screen);
      host.make_pipeline(driver);
      const std::vector<vk::VulkanFrameReport> reports =
          frame_and_resolve(host, driver, f, host.image_with(backgrounds, 0.5f));
      ASSERT_EQ(reports.size(), 1u);
      if (context().info().timestamps) {
        EXPECT_GT(reports[0].resolve_ms, 0.0);
      }
      const TechniqueBuild cpu = build_technique(reports[0].config, {}, f, {}, {}, 1);
      EXPECT_EQ(reports[0].counters, cpu.counters);
      const std::vector<glm::vec4> want = cpu.buffer->composite_image(backgrounds, 1);
      const std::vector<glm::vec4> got = host.read_image();
      ASSERT_EQ(got.size(), want.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < want.size(); ++i) {
        const float transmittance = 1.0f - want[i].a;
        const glm::vec4 expect(glm::vec3(want[i]), want[i].a + transmittance * 0.5f);
        differ += got[i] != expect;
      }
      EXPECT_EQ(differ, 0u) << "of " << want.size() << " pixels";
    }
  }
  // Without timestamps the report waits for the resolve by its event alone.
  const Extent screen{19, 11};
  const TechniqueConfig c = test::technique_config(Technique::SortedLists, screen, Layout::L64);
  vk::VulkanFrameOptions untimed;
  untimed.timestamps = false;
  vk::VulkanFrameDriver driver(context(), c, {}, untimed);
  PointHost host(context(), screen);
  host.make_pipeline(driver);
  const std::vector<glm::vec3> backgrounds(screen.area(), glm::vec3(0.25f, 0.5f, 0.75f));
  const std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 600, 4);
  const std::vector<vk::VulkanFrameReport> reports =
      frame_and_resolve(host, driver, f, host.image_with(backgrounds, 1.0f));
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].gather_ms, 0.0);
  const TechniqueBuild cpu = build_technique(reports[0].config, {}, f, {}, {}, 1);
  const std::vector<glm::vec4> want = cpu.buffer->composite_image(backgrounds, 1);
  const std::vector<glm::vec4> got = host.read_image();
  std::size_t differ = 0;
  for (std::size_t i = 0; i < want.size(); ++i) differ += glm::vec3(got[i]) != glm::vec3(want[i]);
  EXPECT_EQ(differ, 0u);
}

// Frames recorded and submitted together, none waited for: each report is
// its own frame's (the driver's parameter block and counters are shared by
// the frames in flight, ordered by the barriers each frame records), read
// by polling, no fence of the host's waited first.
TEST(VulkanHost, FramesInFlightTogetherEachReportTheirOwnOutcomeWithoutAWait) {
  REQUIRE_VULKAN();
  const Extent screen{40, 24};
  const std::vector<Fragment> a = test::stream(screen, StreamKind::Coherent, 1500, 31);
  const std::vector<Fragment> b = test::stream(screen, StreamKind::Hot, 3800, 32);
  for (Technique t : {Technique::Ha, Technique::SortedLists}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen, Layout::L64);
    if (t == Technique::Ha) c = sized_table(c, b.size());
    if (uses_pool(t)) c.pool_capacity = b.size();
    vk::VulkanFrameDriver driver(context(), c, {});
    PointHost host(context(), screen);
    host.make_pipeline(driver);
    const std::vector<const std::vector<Fragment>*> frames{&a, &b, &a};
    std::vector<VkCommandBuffer> cmds;
    for (const std::vector<Fragment>* f : frames) {
      host.upload(*f);
      cmds.push_back(host.begin());
      driver.record_frame(cmds.back(), host.gather(driver));
    }
    EXPECT_EQ(driver.frames_in_flight(), 3u);
    host.submit_without_wait(cmds);
    std::vector<vk::VulkanFrameReport> reports;
    const auto t0 = std::chrono::steady_clock::now();
    while (reports.size() < frames.size() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
      for (vk::VulkanFrameReport& r : driver.collect_reports()) reports.push_back(std::move(r));
    host.wait();
    ASSERT_EQ(reports.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const TechniqueBuild cpu = build_technique(reports[i].config, {}, *frames[i], {}, {}, 1);
      EXPECT_EQ(reports[i].index, i);
      EXPECT_EQ(reports[i].counters, cpu.counters) << "frame " << i;
    }
  }
}

// SPEC 8 across a host's frames: an automatic table is sized by its first
// frame's report, by size_for, or by a counting gather before its first
// frame (lossless at once); a jump of any size drops records in the frame
// it comes (the table was sized for the frame before), and the next frame
// holds it in one step; a fall shrinks it; a window resize counts again.
TEST(VulkanHost, AnAutomaticTableIsCountedAtItsFirstFrameAndFollowsEveryJumpInOneFrame) {
  REQUIRE_VULKAN();
  const Extent screen{48, 32};
  TechniqueConfig c = test::technique_config(Technique::Ha, screen, Layout::L64);
  c.buffer.table = {};
  const std::vector<Fragment> small = test::stream(screen, StreamKind::Coherent, 900, 3);
  const std::vector<Fragment> large = test::stream(screen, StreamKind::Coherent, 6000, 4);
  {
    // Not counted: the first frame gathers into the screen's table, its
    // report sizes the next (a frame of 6000 fragments into 1536 slots drops
    // most, and the next holds them all).
    vk::VulkanFrameDriver uncounted(context(), c, {});
    PointHost host(context(), screen);
    host.make_pipeline(uncounted);
    const vk::VulkanFrameReport first = one_frame(host, uncounted, large);
    EXPECT_EQ(first.config.buffer.table, screen);
    EXPECT_FALSE(first.counted_fragments.has_value());
    EXPECT_FALSE(first.lossless());
    EXPECT_EQ(first.counters.fragments, large.size());
    const vk::VulkanFrameReport second = one_frame(host, uncounted, large);
    EXPECT_EQ(second.sized_by_frame, 0u);
    EXPECT_TRUE(second.lossless());
    // A host that counted its fragments sizes the next frame itself.
    uncounted.size_for(small.size());
    const vk::VulkanFrameReport sized = one_frame(host, uncounted, small);
    EXPECT_EQ(sized.counted_fragments, small.size());
    EXPECT_TRUE(sized.resized);
    EXPECT_LT(sized.capacity, second.capacity);
    EXPECT_TRUE(sized.lossless());
  }
  vk::VulkanFrameOptions counted;
  counted.count_first_frame = true;
  vk::VulkanFrameDriver driver(context(), c, {}, counted);
  PointHost host(context(), screen);
  host.make_pipeline(driver);
  const vk::VulkanFrameReport first = one_frame(host, driver, small);
  ASSERT_TRUE(first.counted_fragments.has_value());
  EXPECT_EQ(*first.counted_fragments, small.size());
  EXPECT_TRUE(first.lossless());
  const ResizePolicy policy;  // the driver's default band
  const double first_load = static_cast<double>(first.counters.stored()) / static_cast<double>(first.capacity);
  EXPECT_GE(first_load, policy.shrink_at);
  EXPECT_LE(first_load, policy.grow_at);
  // The jump: its frame was sized for the frame before and drops records,
  // every call counted; the next frame holds them, sized by the jump's count.
  const vk::VulkanFrameReport jump = one_frame(host, driver, large);
  EXPECT_FALSE(jump.resized);
  EXPECT_FALSE(jump.lossless());
  EXPECT_EQ(jump.counters.fragments, large.size());
  const vk::VulkanFrameReport held = one_frame(host, driver, large);
  EXPECT_TRUE(held.resized);
  EXPECT_EQ(held.sized_by_frame, jump.index);
  EXPECT_TRUE(held.lossless());
  EXPECT_GT(held.capacity, jump.capacity);
  const TechniqueBuild cpu = build_technique(held.config, {}, large, {}, {}, 1);
  EXPECT_EQ(held.counters, cpu.counters);
  EXPECT_EQ(test::traversed_lists(*driver.read_back()), test::traversed_lists(*cpu.buffer));
  // The fall: the small scene's first frame is judged after it ran (the
  // large table holds it), the next shrinks into the band.
  const vk::VulkanFrameReport fall = one_frame(host, driver, small);
  EXPECT_FALSE(fall.resized);
  EXPECT_TRUE(fall.lossless());
  const vk::VulkanFrameReport shrunk = one_frame(host, driver, small);
  EXPECT_TRUE(shrunk.resized);
  EXPECT_LT(shrunk.capacity, held.capacity);
  EXPECT_TRUE(shrunk.lossless());
  // A window resize: counted again before the next frame, on the new screen.
  const Extent wider{64, 32};
  driver.resize_screen(wider);
  PointHost wide_host(context(), wider);
  wide_host.make_pipeline(driver);
  const std::vector<Fragment> wide = test::stream(wider, StreamKind::Coherent, 2000, 5);
  const vk::VulkanFrameReport after = one_frame(wide_host, driver, wide);
  EXPECT_EQ(after.config.buffer.screen, wider);
  ASSERT_TRUE(after.counted_fragments.has_value());
  EXPECT_EQ(*after.counted_fragments, wide.size());
  EXPECT_TRUE(after.lossless());
}

// A host's own device adopted: the frames run on it, and the features the
// host enabled (not those the device offers) decide what runs.
TEST(VulkanHost, AnAdoptedHostDeviceRunsFramesByTheFeaturesTheHostEnabled) {
  REQUIRE_VULKAN();
  const vk::VulkanInfo& info = context().info();
  vk::HostDevice h;
  h.instance = context().instance();
  h.physical_device = context().physical_device();
  h.device = context().device();
  h.queue = context().queue();
  h.queue_family = context().queue_family();
  h.shader_int64 = info.shader_int64;
  h.buffer_int64_atomics = info.buffer_int64_atomics;
  h.fragment_stores_and_atomics = true;
  const Extent screen{20, 12};
  const TechniqueConfig c = test::technique_config(Technique::Ha, screen, Layout::L64);
  {
    const vk::VulkanContext adopted(h);
    EXPECT_EQ(adopted.info().name, info.name);
    EXPECT_EQ(adopted.device(), context().device());
    vk::VulkanFrameDriver driver(adopted, c, {});
    PointHost host(context(), screen);  // the owning context collects the validation layer's messages
    host.make_pipeline(driver);
    const std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 500, 5);
    const vk::VulkanFrameReport r = one_frame(host, driver, f);
    const TechniqueBuild cpu = build_technique(r.config, {}, f, {}, {}, 1);
    EXPECT_EQ(r.counters, cpu.counters);
  }
  // The adopted context destroyed nothing of the host's: its device still runs frames.
  {
    vk::VulkanFrameDriver driver(context(), c, {});
    PointHost host(context(), screen);
    host.make_pipeline(driver);
    const std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 400, 6);
    const vk::VulkanFrameReport r = one_frame(host, driver, f);
    EXPECT_EQ(r.counters.fragments, f.size());
  }
  if (info.buffer_int64_atomics) {
    vk::HostDevice narrow = h;
    narrow.buffer_int64_atomics = false;  // not enabled by this host: L64 would run emulated64
    const vk::VulkanContext without(narrow);
    EXPECT_FALSE(without.info().buffer_int64_atomics);
    const std::string e = error_of([&] { vk::VulkanFrameDriver d(without, c, {}); });
    EXPECT_NE(e.find("not emulated64"), std::string::npos) << e;
  }
  vk::HostDevice no_stores = h;
  no_stores.fragment_stores_and_atomics = false;
  const std::string e1 = error_of([&] { vk::VulkanContext x(no_stores); });
  EXPECT_NE(e1.find("fragmentStoresAndAtomics"), std::string::npos) << e1;
  const std::string e2 = error_of([&] { vk::VulkanContext x(vk::HostDevice{}); });
  EXPECT_NE(e2.find("must all be given"), std::string::npos) << e2;
  vk::HostDevice far = h;
  far.queue_family = 99;
  const std::string e3 = error_of([&] { vk::VulkanContext x(far); });
  EXPECT_NE(e3.find("queue family 99"), std::string::npos) << e3;
}

TEST(VulkanHost, MisuseOfTheFrameDriverIsRefusedInOneLine) {
  REQUIRE_VULKAN();
  const Extent screen{24, 16};
  const TechniqueConfig c = test::technique_config(Technique::Ha, screen, Layout::L64);
  vk::VulkanFrameDriver driver(context(), c, {});
  PointHost host(context(), screen);
  host.make_pipeline(driver);
  host.upload(test::stream(screen, StreamKind::Coherent, 300, 2));
  const vk::HostImage image = host.image_with(std::vector<glm::vec3>(screen.area(), glm::vec3(0.5f)), 1.0f);
  const auto refused = [&](const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBuffer cmd = host.begin();
    const std::string e = error_of([&] { record(cmd); });
    host.end_and_submit(cmd);  // what was recorded before the refusal is whole and runs clean
    return e;
  };
  std::string e = refused([&](VkCommandBuffer cmd) { driver.record_resolve(cmd, image); });
  EXPECT_NE(e.find("before any record_frame"), std::string::npos) << e;
  {
    // The host's draw without the frame's set: refused, and that command buffer never submitted.
    VkCommandBuffer cmd = host.begin();
    e = error_of([&] { driver.record_frame(cmd, host.gather(driver, false)); });
    EXPECT_NE(e.find("bound no habuffer set"), std::string::npos) << e;
    host.discard(cmd);
    EXPECT_EQ(driver.frames_in_flight(), 0u);
    // The validation layer saw the draw without a set while it was recorded.
    if (context().validation()) {
      const std::vector<std::string> messages = context().take_messages();
      ASSERT_EQ(messages.size(), 1u);
      EXPECT_NE(messages[0].find("descriptor set"), std::string::npos) << messages[0];
    }
  }
  e = refused([&](VkCommandBuffer cmd) { driver.bind(cmd, VK_NULL_HANDLE); });
  EXPECT_NE(e.find("outside a gather"), std::string::npos) << e;
  host.submit([&](VkCommandBuffer cmd) { driver.record_frame(cmd, host.gather(driver)); });
  vk::HostImage small = image;
  small.size = {5, 5};
  e = refused([&](VkCommandBuffer cmd) { driver.record_resolve(cmd, small); });
  EXPECT_NE(e.find("is 5x5, the screen 24x16"), std::string::npos) << e;
  vk::HostImage two_channels = image;
  two_channels.format = VK_FORMAT_R8G8_UNORM;
  e = refused([&](VkCommandBuffer cmd) { driver.record_resolve(cmd, two_channels); });
  EXPECT_NE(e.find("not one the resolve writes"), std::string::npos) << e;
  vk::HostImage undefined = image;
  undefined.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  e = refused([&](VkCommandBuffer cmd) { driver.record_resolve(cmd, undefined); });
  EXPECT_NE(e.find("undefined"), std::string::npos) << e;
  e = refused([&](VkCommandBuffer cmd) {
    driver.record_resolve(cmd, image);
    driver.record_resolve(cmd, image);
  });
  EXPECT_NE(e.find("was resolved already (one resolve a frame)"), std::string::npos) << e;
  EXPECT_EQ(driver.finish_reports().size(), 1u);

  // Frames recorded beyond max_frames_in_flight before any was submitted.
  vk::VulkanFrameOptions two;
  two.max_frames_in_flight = 2;
  vk::VulkanFrameDriver limited(context(), c, {}, two);
  PointHost limited_host(context(), screen);
  limited_host.make_pipeline(limited);
  limited_host.upload(test::stream(screen, StreamKind::Coherent, 300, 2));
  VkCommandBuffer a = limited_host.begin(), b = limited_host.begin();
  limited.record_frame(a, limited_host.gather(limited));
  limited.record_frame(b, limited_host.gather(limited));
  e = refused([&](VkCommandBuffer cmd) { limited.record_frame(cmd, limited_host.gather(limited)); });
  EXPECT_NE(e.find("max_frames_in_flight 2"), std::string::npos) << e;
  limited_host.end_and_submit(a);
  limited_host.end_and_submit(b);
  EXPECT_EQ(limited.finish_reports().size(), 2u);

  // A frame whose command buffer the host drops (a swapchain out of date):
  // forgotten, nothing waits for it, the next frame runs.
  {
    VkCommandBuffer dropped = limited_host.begin();
    limited.record_frame(dropped, limited_host.gather(limited));
    limited_host.discard(dropped);
    EXPECT_EQ(limited.frames_in_flight(), 1u);
    limited.forget_frames_in_flight();
    EXPECT_EQ(limited.frames_in_flight(), 0u);
    e = refused([&](VkCommandBuffer cmd) { limited.record_resolve(cmd, image); });
    EXPECT_NE(e.find("forgotten"), std::string::npos) << e;
    limited_host.submit([&](VkCommandBuffer cmd) { limited.record_frame(cmd, limited_host.gather(limited)); });
    const std::vector<vk::VulkanFrameReport> after = limited.finish_reports();
    ASSERT_EQ(after.size(), 1u);
    EXPECT_EQ(after[0].index, 3u);  // frames 0 and 1 ran, frame 2 was forgotten
  }

  // Calls from another driver's module: the frame's report refuses them.
  const TechniqueConfig lists = test::technique_config(Technique::SortedLists, screen, Layout::L64);
  vk::VulkanFrameDriver other(context(), lists, {});
  host.submit([&](VkCommandBuffer cmd) { other.record_frame(cmd, host.gather(other)); });
  e = error_of([&] { (void)other.finish_reports(); });
  EXPECT_NE(e.find("another module"), std::string::npos) << e;

  // Refused before any device work.
  TechniqueConfig samples = c;
  samples.buffer.samples = 4;
  e = error_of([&] { vk::VulkanFrameDriver d(context(), samples, {}); });
  EXPECT_NE(e.find("one sample"), std::string::npos) << e;
  const TechniqueConfig wboit = test::technique_config(Technique::Wboit, screen, Layout::L64);
  e = error_of([&] { vk::VulkanFrameDriver d(context(), wboit, {}); });
  EXPECT_NE(e.find("does not run wboit"), std::string::npos) << e;
  {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", "emulated64");
    e = error_of([&] { vk::VulkanFrameDriver d(context(), c, {}); });
    EXPECT_NE(e.find("not emulated64"), std::string::npos) << e;
  }
  vk::VulkanFrameOptions none;
  none.max_frames_in_flight = 0;
  e = error_of([&] { vk::VulkanFrameDriver d(context(), c, {}, none); });
  EXPECT_NE(e.find("max_frames_in_flight"), std::string::npos) << e;
  e = error_of([&] { driver.size_for(100); });
  EXPECT_NE(e.find("given its size"), std::string::npos) << e;
}

}  // namespace
}  // namespace habuffer
