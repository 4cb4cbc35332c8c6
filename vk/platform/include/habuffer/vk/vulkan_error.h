/// @file
/// Errors of the Vulkan path: no loader or device, a device without the
/// features the library needs, a shader that does not compile (with its
/// log), a failed call (its VkResult named), or a validation-layer message.
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan_core.h>

namespace habuffer::vk {

/// The exception of the Vulkan path; what() says what failed.
class VulkanError : public std::runtime_error {
 public:
  /// Constructs from a message, as std::runtime_error does.
  using std::runtime_error::runtime_error;
};

/// VK_SUCCESS, VK_ERROR_OUT_OF_DEVICE_MEMORY, ... as text.
std::string result_name(VkResult result);

/// Throws VulkanError "`what`: RESULT" unless `result` is VK_SUCCESS.
void check(VkResult result, const char* what);

}  // namespace habuffer::vk
