// A host Vulkan renderer, written as an engine would be: its own instance
// and device (the validation layer on where it is installed), its own
// colour (RGBA8) and depth (D32) attachments, render passes, pipelines and
// command buffers. Each frame it draws an opaque floor and an opaque box,
// then three translucent panes in no particular order, depth tested against
// the opaque surfaces.
//
// Order-independent transparency comes from habuffer through the lines that
// end in the habuffer tag (grep -c '// \[habuffer\]$' main.cpp counts them):
// the host's device adopted, a frame driver for the HA-buffer, its GLSL
// module in the panes' fragment shader and its set in their pipeline
// layout, the panes' render pass recorded through record_frame, and
// record_resolve compositing the sorted panes over the opaque image. All of
// it is recorded into the host's own command buffer; the host submits.
//
// Exits 0 when the pixels read back match the front-to-back blend computed
// by hand here (within 1.5/255), every frame is lossless and the validation
// layer reported nothing; 1 otherwise.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <habuffer/vk.h>  // [habuffer]

namespace {

constexpr std::uint32_t kWidth = 160, kHeight = 120;
constexpr int kFrames = 3;

// One axis-aligned rectangle in Vulkan's normalized device coordinates (y
// down, z in [0, 1]) with a straight-alpha colour: the push constants.
struct Quad {
  float x0, y0, x1, y1;
  float r, g, b, a;
  float depth;
};
const Quad kFloor{-1.0f, -1.0f, 1.0f, 1.0f, 0.2f, 0.2f, 0.2f, 1.0f, 0.9f};
const Quad kBox{0.5f, -0.5f, 0.9f, 0.5f, 0.9f, 0.9f, 0.1f, 1.0f, 0.1f};  // in front of every pane
const Quad kPanes[3] = {{-0.6f, -0.6f, 0.8f, 0.6f, 1.0f, 0.0f, 0.0f, 0.6f, 0.3f},   // nearest
                        {-0.8f, -0.4f, 0.6f, 0.8f, 0.0f, 0.0f, 1.0f, 0.6f, 0.7f},   // farthest
                        {-0.7f, -0.8f, 0.7f, 0.4f, 0.0f, 1.0f, 0.0f, 0.6f, 0.5f}};  // middle

const char* const kVertex = R"(#version 450
layout(push_constant) uniform HostQuad { vec4 rect; vec4 colour; float depth; } quad;
void main() {
  vec2 corner = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1);
  gl_Position = vec4(mix(quad.rect.xy, quad.rect.zw, corner), quad.depth, 1.0);
}
)";
const char* const kOpaqueFragment = R"(#version 450
layout(push_constant) uniform HostQuad { vec4 rect; vec4 colour; float depth; } quad;
layout(location = 0) out vec4 out_colour;
void main() { out_colour = quad.colour; }
)";
// The panes' gather shader: the driver's module (it starts with #version), then ours.  // [habuffer]
const char* const kPaneMain = R"(                                                          // [habuffer]
layout(early_fragment_tests) in;                                                         // [habuffer]
layout(push_constant) uniform HostQuad { vec4 rect; vec4 colour; float depth; } quad;    // [habuffer]
void main() { habuffer_insert_here(quad.colour); }                                       // [habuffer]
)";                                                                                      // [habuffer]

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

// Warnings and errors of the validation layer, counted and printed.
int g_validation_messages = 0;
VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT type,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (type == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT && severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
    return VK_FALSE;  // the loader's notes
  ++g_validation_messages;
  std::fprintf(stderr, "host_vulkan: validation: %s\n", data->pMessage);
  return VK_FALSE;
}

bool has_validation_layer() {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [](const VkLayerProperties& l) { return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0; });
}

bool inside(const Quad& q, float x, float y) { return x >= q.x0 && x < q.x1 && y >= q.y0 && y < q.y1; }

// What pixel (px, py) must show: the panes in front of the opaque surface
// there, sorted near to far, blended front to back over it, each alpha
// rounded to the 8 bits the records keep.
std::array<double, 3> expected_pixel(std::uint32_t px, std::uint32_t py) {
  const float x = (static_cast<float>(px) + 0.5f) / kWidth * 2.0f - 1.0f;
  const float y = (static_cast<float>(py) + 0.5f) / kHeight * 2.0f - 1.0f;
  const Quad& opaque = inside(kBox, x, y) ? kBox : kFloor;
  std::vector<const Quad*> panes;
  for (const Quad& q : kPanes)
    if (inside(q, x, y) && q.depth < opaque.depth) panes.push_back(&q);
  std::sort(panes.begin(), panes.end(), [](const Quad* a, const Quad* b) { return a->depth < b->depth; });
  std::array<double, 3> c{0, 0, 0};
  double transmittance = 1.0;
  for (const Quad* q : panes) {
    const double a = std::round(q->a * 255.0) / 255.0, w = transmittance * a;
    c[0] += w * q->r;
    c[1] += w * q->g;
    c[2] += w * q->b;
    transmittance *= 1.0 - a;
  }
  return {c[0] + transmittance * opaque.r, c[1] + transmittance * opaque.g, c[2] + transmittance * opaque.b};
}

// The host's renderer: everything a small Vulkan engine makes for itself.
struct Renderer {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  bool int64 = false, int64_atomics = false;
  VkImage colour = VK_NULL_HANDLE, depth = VK_NULL_HANDLE;
  VkDeviceMemory colour_memory = VK_NULL_HANDLE, depth_memory = VK_NULL_HANDLE;
  VkImageView colour_view = VK_NULL_HANDLE, depth_view = VK_NULL_HANDLE;
  VkRenderPass opaque_pass = VK_NULL_HANDLE, pane_pass = VK_NULL_HANDLE;
  VkFramebuffer opaque_fb = VK_NULL_HANDLE, pane_fb = VK_NULL_HANDLE;
  VkPipelineLayout opaque_layout = VK_NULL_HANDLE, pane_layout = VK_NULL_HANDLE;
  VkPipeline opaque_pipeline = VK_NULL_HANDLE, pane_pipeline = VK_NULL_HANDLE;
  std::vector<VkShaderModule> modules;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkBuffer readback = VK_NULL_HANDLE;
  VkDeviceMemory readback_memory = VK_NULL_HANDLE;

  void make_instance() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "host_vulkan";
    app.apiVersion = VK_API_VERSION_1_2;
    const bool validation = has_validation_layer();
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mi.pfnUserCallback = on_message;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    if (validation) {
      ci.enabledLayerCount = 1;
      ci.ppEnabledLayerNames = &layer;
      ci.enabledExtensionCount = 1;
      ci.ppEnabledExtensionNames = &extension;
      ci.pNext = &mi;
    }
    check(vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      check(create(instance, &mi, nullptr, &messenger), "the validation messenger");
    }
    std::printf("host_vulkan: validation layer %s\n", validation ? "on" : "not installed");
  }

  void make_device() {
    std::uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance, &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance, &n, devices.data());
    for (VkPhysicalDevice d : devices) {
      std::uint32_t f = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(d, &f, nullptr);
      std::vector<VkQueueFamilyProperties> props(f);
      vkGetPhysicalDeviceQueueFamilyProperties(d, &f, props.data());
      for (std::uint32_t i = 0; i < f && physical == VK_NULL_HANDLE; ++i)
        if ((props[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
          physical = d;
          family = i;
        }
    }
    if (physical == VK_NULL_HANDLE) throw std::runtime_error("no Vulkan device with a graphics and compute queue");
    VkPhysicalDeviceVulkan12Features offered12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 offered{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    offered.pNext = &offered12;
    vkGetPhysicalDeviceFeatures2(physical, &offered);
    if (!offered.features.fragmentStoresAndAtomics) throw std::runtime_error("no fragmentStoresAndAtomics");
    int64 = offered.features.shaderInt64 == VK_TRUE;
    int64_atomics = int64 && offered12.shaderBufferInt64Atomics == VK_TRUE;
    // The features habuffer's module needs, enabled by the host.
    VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    enable12.shaderBufferInt64Atomics = int64_atomics ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    enable.pNext = &enable12;
    enable.features.shaderInt64 = int64 ? VK_TRUE : VK_FALSE;
    enable.features.fragmentStoresAndAtomics = VK_TRUE;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = family;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.pNext = &enable;
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    check(vkCreateDevice(physical, &di, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, family, 0, &queue);
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pi.queueFamilyIndex = family;
    check(vkCreateCommandPool(device, &pi, nullptr, &pool), "vkCreateCommandPool");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device, &fi, nullptr, &fence), "vkCreateFence");
  }

  std::uint32_t memory_type(std::uint32_t bits, VkMemoryPropertyFlags want) const {
    VkPhysicalDeviceMemoryProperties props{};
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    for (std::uint32_t t = 0; t < props.memoryTypeCount; ++t)
      if ((bits & (1u << t)) != 0 && (props.memoryTypes[t].propertyFlags & want) == want) return t;
    throw std::runtime_error("no memory type");
  }

  void make_image(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage& image,
                  VkDeviceMemory& memory, VkImageView& view) {
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = format;
    ii.extent = {kWidth, kHeight, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    check(vkCreateImage(device, &ii, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
    check(vkBindImageMemory(device, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    check(vkCreateImageView(device, &vi, nullptr, &view), "vkCreateImageView");
  }

  void make_targets() {
    // The colour target is also a storage image: habuffer's resolve composites into it in place.
    make_image(VK_FORMAT_R8G8B8A8_UNORM,
               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                   VK_IMAGE_USAGE_STORAGE_BIT,  // [habuffer]
               VK_IMAGE_ASPECT_COLOR_BIT, colour, colour_memory, colour_view);
    make_image(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, depth,
               depth_memory, depth_view);
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = kWidth * kHeight * 4;
    bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    check(vkCreateBuffer(device, &bi, nullptr, &readback), "vkCreateBuffer");
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, readback, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkAllocateMemory(device, &ai, nullptr, &readback_memory), "vkAllocateMemory");
    check(vkBindBufferMemory(device, readback, readback_memory, 0), "vkBindBufferMemory");
  }

  // The opaque pass clears and draws colour and depth; the panes' pass
  // tests against that depth and writes no attachment.
  void make_passes() {
    VkAttachmentDescription a[2]{};
    a[0].format = VK_FORMAT_R8G8B8A8_UNORM;
    a[0].samples = VK_SAMPLE_COUNT_1_BIT;
    a[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a[1] = a[0];
    a[1].format = VK_FORMAT_D32_SFLOAT;
    a[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    const VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &colour_ref;
    sub.pDepthStencilAttachment = &depth_ref;
    // The previous frame's reads of the colour target (its copy) before this clear.
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                       VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dep.srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 2;
    rp.pAttachments = a;
    rp.subpassCount = 1;
    rp.pSubpasses = &sub;
    rp.dependencyCount = 1;
    rp.pDependencies = &dep;
    check(vkCreateRenderPass(device, &rp, nullptr, &opaque_pass), "the opaque render pass");
    VkAttachmentDescription d = a[1];
    d.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    d.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    d.initialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    VkSubpassDescription pane_sub{};
    pane_sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    const VkAttachmentReference pane_depth{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    pane_sub.pDepthStencilAttachment = &pane_depth;
    VkSubpassDependency after_opaque{};
    after_opaque.srcSubpass = VK_SUBPASS_EXTERNAL;
    after_opaque.dstSubpass = 0;
    after_opaque.srcStageMask = VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    after_opaque.dstStageMask = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    after_opaque.srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    after_opaque.dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    rp.attachmentCount = 1;
    rp.pAttachments = &d;
    rp.pSubpasses = &pane_sub;
    rp.pDependencies = &after_opaque;
    check(vkCreateRenderPass(device, &rp, nullptr, &pane_pass), "the panes' render pass");
    const VkImageView both[2] = {colour_view, depth_view};
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = opaque_pass;
    fb.attachmentCount = 2;
    fb.pAttachments = both;
    fb.width = kWidth;
    fb.height = kHeight;
    fb.layers = 1;
    check(vkCreateFramebuffer(device, &fb, nullptr, &opaque_fb), "the opaque framebuffer");
    fb.renderPass = pane_pass;
    fb.attachmentCount = 1;
    fb.pAttachments = &depth_view;
    check(vkCreateFramebuffer(device, &fb, nullptr, &pane_fb), "the panes' framebuffer");
  }

  VkShaderModule shader(const std::vector<std::uint32_t>& spirv) {
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = spirv.size() * 4;
    mi.pCode = spirv.data();
    VkShaderModule m = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device, &mi, nullptr, &m), "vkCreateShaderModule");
    modules.push_back(m);
    return m;
  }

  // A pipeline drawing one quad (a 4-vertex strip) of the push constants.
  VkPipeline make_pipeline(VkShaderModule vs, VkShaderModule fs, VkPipelineLayout layout, VkRenderPass pass,
                           bool opaque) {
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs, "main",
                 nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs,
                 "main", nullptr};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    const VkViewport viewport{0, 0, static_cast<float>(kWidth), static_cast<float>(kHeight), 0, 1};
    const VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.pViewports = &viewport;
    vp.scissorCount = 1;
    vp.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = VK_TRUE;
    ds.depthWriteEnable = opaque ? VK_TRUE : VK_FALSE;  // the panes test against the opaque depth, write none
    ds.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = opaque ? 1 : 0;
    cb.pAttachments = &blend;
    VkGraphicsPipelineCreateInfo pi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    pi.stageCount = 2;
    pi.pStages = stages;
    pi.pVertexInputState = &vi;
    pi.pInputAssemblyState = &ia;
    pi.pViewportState = &vp;
    pi.pRasterizationState = &rs;
    pi.pMultisampleState = &ms;
    pi.pDepthStencilState = &ds;
    pi.pColorBlendState = &cb;
    pi.layout = layout;
    pi.renderPass = pass;
    VkPipeline p = VK_NULL_HANDLE;
    check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &pi, nullptr, &p), "vkCreateGraphicsPipelines");
    return p;
  }

  VkPipelineLayout make_layout(const VkDescriptorSetLayout* set) {
    const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Quad)};
    VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    li.setLayoutCount = set != nullptr ? 1 : 0;
    li.pSetLayouts = set;
    li.pushConstantRangeCount = 1;
    li.pPushConstantRanges = &push;
    VkPipelineLayout l = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device, &li, nullptr, &l), "vkCreatePipelineLayout");
    return l;
  }

  void draw(VkCommandBuffer cmd, VkPipelineLayout layout, const Quad& q) const {
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof q, &q);
    vkCmdDraw(cmd, 4, 1, 0, 0);
  }

  void begin_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer fb, bool clear) const {
    VkClearValue values[2]{};
    values[0].color = {{0.0f, 0.0f, 0.0f, 1.0f}};
    values[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rb.renderPass = pass;
    rb.framebuffer = fb;
    rb.renderArea = {{0, 0}, {kWidth, kHeight}};
    rb.clearValueCount = clear ? 2 : 0;
    rb.pClearValues = values;
    vkCmdBeginRenderPass(cmd, &rb, VK_SUBPASS_CONTENTS_INLINE);
  }

  // The colour target copied to the read-back buffer (the frame's last commands).
  void record_readback(VkCommandBuffer cmd) const {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = colour;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
    const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {kWidth, kHeight, 1}};
    vkCmdCopyImageToBuffer(cmd, colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &region);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                         nullptr);
  }

  void destroy() {
    if (device == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device);
    for (VkPipeline p : {opaque_pipeline, pane_pipeline}) vkDestroyPipeline(device, p, nullptr);
    for (VkPipelineLayout l : {opaque_layout, pane_layout}) vkDestroyPipelineLayout(device, l, nullptr);
    for (VkShaderModule m : modules) vkDestroyShaderModule(device, m, nullptr);
    for (VkFramebuffer f : {opaque_fb, pane_fb}) vkDestroyFramebuffer(device, f, nullptr);
    for (VkRenderPass r : {opaque_pass, pane_pass}) vkDestroyRenderPass(device, r, nullptr);
    for (VkImageView v : {colour_view, depth_view}) vkDestroyImageView(device, v, nullptr);
    for (VkImage i : {colour, depth}) vkDestroyImage(device, i, nullptr);
    for (VkDeviceMemory m : {colour_memory, depth_memory, readback_memory}) vkFreeMemory(device, m, nullptr);
    vkDestroyBuffer(device, readback, nullptr);
    vkDestroyFence(device, fence, nullptr);
    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
    if (messenger != VK_NULL_HANDLE) {
      auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      destroy_messenger(instance, messenger, nullptr);
    }
    vkDestroyInstance(instance, nullptr);
    device = VK_NULL_HANDLE;
  }
};

int run(Renderer& host) {
  host.make_instance();
  host.make_device();
  host.make_targets();
  host.make_passes();

  namespace hb = habuffer;                                                       // [habuffer]
  hb::vk::HostDevice adopted;                                                    // [habuffer]
  adopted.instance = host.instance;                                              // [habuffer]
  adopted.physical_device = host.physical;                                       // [habuffer]
  adopted.device = host.device;                                                  // [habuffer]
  adopted.queue = host.queue;                                                    // [habuffer]
  adopted.queue_family = host.family;                                            // [habuffer]
  adopted.shader_int64 = host.int64;                                             // [habuffer]
  adopted.buffer_int64_atomics = host.int64_atomics;                             // [habuffer]
  adopted.fragment_stores_and_atomics = true;                                    // [habuffer]
  const hb::vk::VulkanContext context(adopted);                                  // [habuffer]
  hb::TechniqueConfig config;                                                    // [habuffer]
  config.technique = hb::Technique::Ha;                                          // [habuffer]
  config.buffer.screen = {kWidth, kHeight};                                      // [habuffer]
  // No table given: the first frame's report sizes the next, and so on (SPEC 8).
  hb::vk::VulkanFrameDriver oit(context, config, hb::OffsetSource{});            // [habuffer]
  std::printf("host_vulkan: %s, %s\n", context.info().name.c_str(), hb::to_string(oit.mode()).c_str());  // [habuffer]

  const VkShaderModule vertex = host.shader(hb::vk::compile_to_spirv(kVertex, hb::vk::SpirvStage::Vertex, "vertex"));
  const VkShaderModule opaque_fragment =
      host.shader(hb::vk::compile_to_spirv(kOpaqueFragment, hb::vk::SpirvStage::Fragment, "opaque fragment"));
  const VkShaderModule pane_fragment = host.shader(oit.compile_gather_fragment(kPaneMain));  // [habuffer]
  host.opaque_layout = host.make_layout(nullptr);
  const VkDescriptorSetLayout oit_set = oit.set_layout();  // set 0 of the panes' layout  // [habuffer]
  host.pane_layout = host.make_layout(&oit_set);                                           // [habuffer]
  host.opaque_pipeline = host.make_pipeline(vertex, opaque_fragment, host.opaque_layout, host.opaque_pass, true);
  host.pane_pipeline = host.make_pipeline(vertex, pane_fragment, host.pane_layout, host.pane_pass, false);

  std::vector<hb::vk::VulkanFrameReport> reports;  // [habuffer]
  for (int frame = 0; frame < kFrames; ++frame) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = host.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(host.device, &ai, &cmd), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    host.begin_pass(cmd, host.opaque_pass, host.opaque_fb, true);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, host.opaque_pipeline);
    host.draw(cmd, host.opaque_layout, kFloor);
    host.draw(cmd, host.opaque_layout, kBox);
    vkCmdEndRenderPass(cmd);
    oit.record_frame(cmd, [&](VkCommandBuffer gather) {                          // [habuffer]
      host.begin_pass(gather, host.pane_pass, host.pane_fb, false);
      vkCmdBindPipeline(gather, VK_PIPELINE_BIND_POINT_GRAPHICS, host.pane_pipeline);
      oit.bind(gather, host.pane_layout);                                        // [habuffer]
      for (const Quad& q : kPanes) host.draw(gather, host.pane_layout, q);
      vkCmdEndRenderPass(gather);
    });                                                                          // [habuffer]
    oit.record_resolve(cmd, {host.colour, host.colour_view, VK_FORMAT_R8G8B8A8_UNORM, {kWidth, kHeight},  // [habuffer]
                             VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});                                   // [habuffer]
    host.record_readback(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(host.queue, 1, &si, host.fence), "vkQueueSubmit");
    check(vkWaitForFences(host.device, 1, &host.fence, VK_TRUE, 60'000'000'000ull), "vkWaitForFences");
    check(vkResetFences(host.device, 1, &host.fence), "vkResetFences");
    vkFreeCommandBuffers(host.device, host.pool, 1, &cmd);
    for (hb::vk::VulkanFrameReport& r : oit.collect_reports()) reports.push_back(r);  // [habuffer]
  }
  for (const hb::vk::VulkanFrameReport& r : oit.finish_reports()) reports.push_back(r);  // [habuffer]
  // The first frame gathered into the screen's table and sized the next by
  // its report (SPEC 8): from the second on, every frame is lossless, and
  // every frame counted every fragment.
  bool lossless = reports.size() == kFrames;                                              // [habuffer]
  for (const hb::vk::VulkanFrameReport& r : reports) {                                    // [habuffer]
    std::printf("habuffer: frame %llu: %llu fragments, %llu lost, table %s, gather %.3f ms, resolve %.3f ms\n",  // [habuffer]
                (unsigned long long)r.index, (unsigned long long)r.counters.fragments,                   // [habuffer]
                (unsigned long long)r.counters.failures(), r.config.buffer.table.str().c_str(), r.gather_ms,  // [habuffer]
                r.resolve_ms);                                                                           // [habuffer]
    lossless = lossless && (r.index == 0 || r.lossless()) &&                                            // [habuffer]
               r.counters.fragments == reports.front().counters.fragments && r.counters.fragments > 0;   // [habuffer]
  }                                                                                                      // [habuffer]

  void* mapped = nullptr;
  check(vkMapMemory(host.device, host.readback_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  const auto* pixels = static_cast<const std::uint8_t*>(mapped);
  int wrong = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::array<double, 3> want = expected_pixel(x, y);
      for (int ch = 0; ch < 3; ++ch) {
        const double got = pixels[4 * (y * kWidth + x) + ch] / 255.0;
        if (std::abs(got - want[ch]) > 1.5 / 255.0 && wrong++ < 5)
          std::fprintf(stderr, "host_vulkan: pixel (%u, %u) channel %d is %.4f, expected %.4f\n", x, y, ch, got,
                       want[ch]);
      }
    }
  vkUnmapMemory(host.device, host.readback_memory);
  std::printf("host_vulkan: %d wrong channels, %d validation messages\n", wrong, g_validation_messages);
  return wrong == 0 && lossless && g_validation_messages == 0 ? 0 : 1;  // [habuffer]
}

}  // namespace

int main() {
  Renderer host;
  int status = 1;
  try {
    status = run(host);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_vulkan: %s\n", e.what());
  }
  host.destroy();
  return status;
}
