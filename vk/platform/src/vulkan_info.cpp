#include "habuffer/vk/vulkan_info.h"

#include <cstdio>
#include <stdexcept>

#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {

namespace {

const char* type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

std::string version_text(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

}  // namespace

VulkanInfo query_vulkan_info(VkPhysicalDevice device, std::uint32_t index) {
  VulkanInfo i;
  i.index = index;
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(device, &props);
  i.name = props.deviceName;
  i.type = type_name(props.deviceType);
  i.api = props.apiVersion;
  i.api_version = version_text(props.apiVersion);
  i.software = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  i.timestamp_period_ns = props.limits.timestampPeriod;
  i.timestamps = props.limits.timestampComputeAndGraphics == VK_TRUE;
  i.max_storage_range = props.limits.maxStorageBufferRange;
  i.max_work_groups_x = props.limits.maxComputeWorkGroupCount[0];
  i.max_work_groups_y = props.limits.maxComputeWorkGroupCount[1];
  i.max_framebuffer_width = props.limits.maxFramebufferWidth;
  i.max_framebuffer_height = props.limits.maxFramebufferHeight;
  i.max_push_constants = props.limits.maxPushConstantsSize;
  if (props.apiVersion < VK_API_VERSION_1_2) {
    i.unusable = "Vulkan " + i.api_version + " (the library needs 1.2)";
    return i;
  }
  VkPhysicalDeviceVulkan12Features v12{};
  v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &v12;
  vkGetPhysicalDeviceFeatures2(device, &features);
  i.shader_int64 = features.features.shaderInt64 == VK_TRUE;
  i.buffer_int64_atomics = i.shader_int64 && v12.shaderBufferInt64Atomics == VK_TRUE;
  i.fragment_stores = features.features.fragmentStoresAndAtomics == VK_TRUE;
  VkPhysicalDeviceVulkan12Properties p12{};
  p12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES;
  VkPhysicalDeviceProperties2 props2{};
  props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  props2.pNext = &p12;
  vkGetPhysicalDeviceProperties2(device, &props2);
  i.driver = p12.driverName;
  i.lavapipe = p12.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  if (p12.driverInfo[0] != '\0') {
    i.driver += ' ';
    i.driver.append(p12.driverInfo);
  }
  if (!i.fragment_stores) i.unusable = "no fragmentStoresAndAtomics (a gather's fragment shader writes buffers)";
  return i;
}

AtomicSupport atomic_support(const VulkanInfo& info) {
  return {info.shader_int64, info.buffer_int64_atomics, "Vulkan device", info.name, "shaderInt64",
          "shaderBufferInt64Atomics"};
}

std::vector<AtomicMode> runnable_atomic_modes(const VulkanInfo& info) {
  return habuffer::runnable_atomic_modes(atomic_support(info));
}

std::optional<AtomicMode> chosen_atomic_mode(const VulkanInfo& info, Layout layout) {
  std::optional<AtomicMode> mode;
  try {
    // A 64-bit mode forced beside L32 is said at once: the Vulkan path has no
    // once-per-process log of its own yet, and the choice is made once per build.
    mode = habuffer::chosen_atomic_mode(atomic_support(info), layout,
                                        [](const std::string& m) { std::fprintf(stderr, "habuffer vk: %s\n", m.c_str()); });
  } catch (const std::invalid_argument& e) {
    throw VulkanError(e.what());
  }
  return mode;
}

}  // namespace habuffer::vk
