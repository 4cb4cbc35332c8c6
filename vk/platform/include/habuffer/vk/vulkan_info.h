/// @file
/// What a Vulkan device offers the library, and which atomic modes of the
/// HA-buffer it runs (chosen by every path's one rule, habuffer/atomic_mode.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/atomic_mode.h"
#include "habuffer/record_layout.h"

namespace habuffer::vk {

/// A physical device's name, driver and the features and limits the library reads.
struct VulkanInfo {
  std::uint32_t index = 0;             ///< its place in vkEnumeratePhysicalDevices' list
  std::string name;                    ///< VkPhysicalDeviceProperties::deviceName
  std::string type;                    ///< "discrete GPU", "integrated GPU", "CPU", ...
  std::string driver;                  ///< driverName and driverInfo (Vulkan 1.2)
  std::string api_version;             ///< "1.3.239"
  std::uint32_t api = 0;               ///< VkPhysicalDeviceProperties::apiVersion
  bool shader_int64 = false;           ///< shaderInt64
  bool buffer_int64_atomics = false;   ///< shaderBufferInt64Atomics (Vulkan 1.2)
  bool fragment_stores = false;        ///< fragmentStoresAndAtomics
  bool timestamps = false;             ///< timestampComputeAndGraphics
  float timestamp_period_ns = 0.0f;    ///< nanoseconds per timestamp tick
  std::uint64_t max_storage_range = 0;  ///< maxStorageBufferRange (bytes one binding sees)
  std::uint32_t max_work_groups_x = 0;  ///< maxComputeWorkGroupCount[0]
  std::uint32_t max_work_groups_y = 0;  ///< maxComputeWorkGroupCount[1]
  std::uint32_t max_framebuffer_width = 0, max_framebuffer_height = 0;
  std::uint32_t max_push_constants = 0;  ///< maxPushConstantsSize (bytes)
  /// A device that runs shaders on the CPU (VK_PHYSICAL_DEVICE_TYPE_CPU:
  /// lavapipe): its atomics are locked read-modify-writes of cache lines.
  bool software = false;
  /// Mesa's lavapipe (driverID VK_DRIVER_ID_MESA_LLVMPIPE): its atomics are
  /// sequentially consistent operations on host memory, and a memory
  /// barrier in a divergent branch ends the lanes there (vulkan_device_defines).
  bool lavapipe = false;
  /// Why the library cannot run on it (one line), empty where it can.
  std::string unusable;
};

/// Reads a physical device's properties and features (index: its place in the list).
VulkanInfo query_vulkan_info(VkPhysicalDevice device, std::uint32_t index);

/// What the device offers the atomic modes, in Vulkan's words.
AtomicSupport atomic_support(const VulkanInfo& info);
/// Modes the Vulkan path runs on the device, in order of preference (every
/// path's rule: habuffer::runnable_atomic_modes).
std::vector<AtomicMode> runnable_atomic_modes(const VulkanInfo& info);
/// The mode a layout runs in on this device: every path's rule
/// (habuffer::chosen_atomic_mode), its errors VulkanError.
std::optional<AtomicMode> chosen_atomic_mode(const VulkanInfo& info, Layout layout);

}  // namespace habuffer::vk
