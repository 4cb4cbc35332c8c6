/// @file
/// A headless Vulkan instance and device: no window, no surface, one queue
/// that runs compute and graphics. The device is chosen by index or by name
/// (DeviceChoice; lavapipe on a machine without a GPU, the GPU's driver where
/// one is); with validation on, every message of the Khronos validation layer
/// is collected and raised as VulkanError at the next check.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/vk/vulkan_info.h"

namespace habuffer::vk {

/// Which physical device to use: by its index in the loader's list, or the
/// first whose name contains `name` (case-insensitive); with neither, the
/// first usable device, a GPU before a CPU device.
struct DeviceChoice {
  std::optional<std::uint32_t> index;
  std::string name;
  /// HABUFFER_VK_DEVICE: a number is an index, anything else a name; unset: no choice.
  static DeviceChoice from_environment();
  /// "device 1", "device named \"llvmpipe\"" or "the first usable device".
  [[nodiscard]] std::string str() const;
};

/// How a context is made.
struct ContextOptions {
  DeviceChoice device = DeviceChoice::from_environment();
  /// The Khronos validation layer and its messages as errors (default:
  /// HABUFFER_VK_VALIDATION=1). Asked for where the layer is not installed:
  /// VulkanError naming the package (vulkan-validationlayers).
  bool validation = validation_from_environment();
  /// HABUFFER_VK_VALIDATION is 1 (0 or unset: off; anything else: VulkanError).
  static bool validation_from_environment();
};

/// Whether the Khronos validation layer is installed (Debian vulkan-validationlayers).
bool validation_layer_available();

/// Every physical device the loader lists, each with why it cannot be used
/// (VulkanInfo::unusable); throws VulkanError without a loader or an ICD.
std::vector<VulkanInfo> list_devices();

/// A host's own Vulkan device, for a context that adopts it (a Vulkan
/// engine embedding the library): the handles the host made, which the
/// context uses and never destroys, and the features the host enabled at
/// vkCreateDevice (Vulkan cannot be asked afterwards).
struct HostDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  /// A queue of `queue_family`, which must run graphics and compute. The
  /// context submits on it only in its waits (a buffer made or read, the
  /// counting gather of an automatic container's first frame): the host
  /// must not submit to it from another thread meanwhile.
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  bool shader_int64 = false;                 ///< VkPhysicalDeviceFeatures::shaderInt64 enabled
  bool buffer_int64_atomics = false;         ///< VkPhysicalDeviceVulkan12Features::shaderBufferInt64Atomics enabled
  bool fragment_stores_and_atomics = false;  ///< VkPhysicalDeviceFeatures::fragmentStoresAndAtomics enabled (needed)
};

/// The instance, the chosen device and its queue. Not copyable; destroys
/// everything it made.
class VulkanContext {
 public:
  /// Throws VulkanError in one line: no Vulkan loader or device, a device
  /// choice that matches none (naming the devices there are), a device
  /// without what the library needs (naming the feature), the validation
  /// layer asked for but missing.
  explicit VulkanContext(const ContextOptions& options = {});
  /// Adopts a host's device: info() is its device's, with the features the
  /// host did not enable taken away (so the atomic modes follow what it
  /// enabled). Throws VulkanError in one line for a null handle, a queue
  /// family without graphics and compute, a device below Vulkan 1.2 or
  /// without fragmentStoresAndAtomics enabled. Validation is the host's
  /// (its own messenger): validation() is false and check_messages finds none.
  explicit VulkanContext(const HostDevice& host);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  [[nodiscard]] VkInstance instance() const;
  [[nodiscard]] VkPhysicalDevice physical_device() const;
  [[nodiscard]] VkDevice device() const;
  [[nodiscard]] VkQueue queue() const;
  [[nodiscard]] std::uint32_t queue_family() const;
  [[nodiscard]] const VulkanInfo& info() const;
  /// Whether the validation layer watches this context.
  [[nodiscard]] bool validation() const;

  /// Records commands into a fresh primary command buffer, submits it and
  /// waits for it (at most `timeout_ms`; beyond: VulkanError, the device
  /// left to finish before the context goes). Then check_messages(what).
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record, const char* what,
                       std::uint64_t timeout_ms = 600000) const;

  /// Validation messages (warnings and errors) collected since the last check.
  [[nodiscard]] std::vector<std::string> take_messages() const;
  /// Throws VulkanError naming `where` and the first collected message (and
  /// how many more) when there is any; clears them either way.
  void check_messages(const char* where) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace habuffer::vk
