// What every Vulkan test file shares: the skip where the machine has no
// usable device, one validated context a process, scoped environment
// settings, and an error's text.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "habuffer/vk.h"

namespace habuffer {

// Skips a test where the machine has no usable Vulkan device (the library's
// message says why); every Vulkan test's first line.
#define REQUIRE_VULKAN()                                                         \
  do {                                                                           \
    if (const std::string why = vulkan_missing(); !why.empty()) GTEST_SKIP() << why; \
  } while (0)

inline std::string vulkan_missing() {
  try {
    for (const vk::VulkanInfo& d : vk::list_devices())
      if (d.unusable.empty()) return {};
    return "no usable Vulkan device";
  } catch (const vk::VulkanError& e) {
    return e.what();
  }
}

// One context a process, validation on: devices are costly to make.
inline const vk::VulkanContext& context() {
  static const vk::VulkanContext c([] {
    vk::ContextOptions o;
    // The device HABUFFER_VK_DEVICE names; validation on where the layer is
    // installed, unless HABUFFER_VK_VALIDATION says otherwise (the lent GPU
    // machine has no layer: scripts/gpu_checks.sh sets 0).
    o.validation = std::getenv("HABUFFER_VK_VALIDATION") != nullptr ? vk::ContextOptions::validation_from_environment()
                                                                     : vk::validation_layer_available();
    return o;
  }());
  return c;
}

// An environment variable set (or, with nullptr, unset) for one scope,
// restored after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* was = std::getenv(name)) before_ = was;
    if (value != nullptr)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (before_)
      setenv(name_, before_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> before_;
};

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace habuffer
