#include "habuffer/vk/vulkan_context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <utility>

#include "habuffer/vk/vulkan_error.h"

namespace habuffer::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool layer_present(const char* name) {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

// An instance of Vulkan 1.2 with nothing enabled but, optionally, validation.
VkInstance make_instance(bool validation, void* messenger_info) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "habuffer";
  app.pEngineName = "habuffer";
  app.apiVersion = VK_API_VERSION_1_2;
  const char* layers[] = {kValidationLayer};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ci.pApplicationInfo = &app;
  if (validation) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = layers;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = extensions;
    ci.pNext = messenger_info;  // messages of vkCreateInstance itself too
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw VulkanError("no Vulkan driver (ICD): install one (lavapipe: Debian mesa-vulkan-drivers)");
  check(r, "creating a Vulkan instance");
  return instance;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  std::uint32_t n = 0;
  check(vkEnumeratePhysicalDevices(instance, &n, nullptr), "listing Vulkan devices");
  std::vector<VkPhysicalDevice> devices(n);
  check(vkEnumeratePhysicalDevices(instance, &n, devices.data()), "listing Vulkan devices");
  devices.resize(n);
  return devices;
}

// The first queue family that runs compute and graphics (every Vulkan
// implementation with graphics has one).
std::optional<std::uint32_t> universal_family(VkPhysicalDevice device) {
  std::uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, families.data());
  const VkQueueFlags want = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
  for (std::uint32_t f = 0; f < n; ++f)
    if ((families[f].queueFlags & want) == want && families[f].queueCount > 0) return f;
  return std::nullopt;
}

VulkanInfo usable_info(VkPhysicalDevice device, std::uint32_t index) {
  VulkanInfo info = query_vulkan_info(device, index);
  if (info.unusable.empty() && !universal_family(device)) info.unusable = "no queue that runs compute and graphics";
  return info;
}

std::string device_list(const std::vector<VulkanInfo>& infos) {
  std::string s;
  for (const VulkanInfo& i : infos)
    s += (s.empty() ? "" : ", ") + std::to_string(i.index) + ": " + i.name + (i.unusable.empty() ? "" : " (unusable)");
  return s.empty() ? "none" : s;
}

int preference(const VulkanInfo& i) {
  if (i.type == "discrete GPU") return 0;
  if (i.type == "integrated GPU") return 1;
  if (i.type == "CPU") return 3;
  return 2;
}

}  // namespace

DeviceChoice DeviceChoice::from_environment() {
  DeviceChoice c;
  const char* env = std::getenv("HABUFFER_VK_DEVICE");
  if (env == nullptr || *env == '\0') return c;
  const std::string text(env);
  if (std::all_of(text.begin(), text.end(), [](unsigned char ch) { return std::isdigit(ch) != 0; }) && text.size() < 10)
    c.index = static_cast<std::uint32_t>(std::stoul(text));
  else
    c.name = text;
  return c;
}

std::string DeviceChoice::str() const {
  if (index) return "device " + std::to_string(*index);
  if (!name.empty()) return "device named \"" + name + "\"";
  return "the first usable device";
}

bool ContextOptions::validation_from_environment() {
  const char* env = std::getenv("HABUFFER_VK_VALIDATION");
  if (env == nullptr || *env == '\0' || std::strcmp(env, "0") == 0) return false;
  if (std::strcmp(env, "1") == 0) return true;
  throw VulkanError("HABUFFER_VK_VALIDATION='" + std::string(env) + "' is not 0 or 1");
}

bool validation_layer_available() { return layer_present(kValidationLayer); }

std::vector<VulkanInfo> list_devices() {
  const VkInstance instance = make_instance(false, nullptr);
  std::vector<VulkanInfo> infos;
  try {
    const auto devices = physical_devices(instance);
    for (std::uint32_t i = 0; i < devices.size(); ++i) infos.push_back(usable_info(devices[i], i));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return infos;
}

struct VulkanContext::State {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VulkanInfo info;
  bool validation = false;
  bool adopted = false;  // the instance and device are a host's: never destroyed here
  mutable std::mutex mutex;
  mutable std::vector<std::string> messages;

  ~State() {
    if (device != VK_NULL_HANDLE) {
      // A host's device: only the queue this context submits to, not the
      // host's other queues (which its other threads may be using).
      if (adopted)
        vkQueueWaitIdle(queue);
      else
        vkDeviceWaitIdle(device);
      if (pool != VK_NULL_HANDLE) vkDestroyCommandPool(device, pool, nullptr);
      if (!adopted) vkDestroyDevice(device, nullptr);
    }
    if (adopted) return;
    if (messenger != VK_NULL_HANDLE) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy != nullptr) destroy(instance, messenger, nullptr);
    }
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
  }

  // The pool of submit_and_wait's command buffers, on the queue's family.
  void make_pool() {
    VkCommandPoolCreateInfo created{};
    created.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    created.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    created.queueFamilyIndex = family;
    check(vkCreateCommandPool(device, &created, nullptr, &pool), "creating a command pool");
  }

  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT type,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    // The loader's general warnings (a stray ICD manifest) are not the
    // library's errors; its general errors, and every validation or
    // performance message, are.
    if (type == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT && severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
      return VK_FALSE;
    auto* s = static_cast<State*>(user);
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    const std::lock_guard lock(s->mutex);
    s->messages.push_back(std::string("validation ") + level + ": " + (data->pMessage ? data->pMessage : "?"));
    return VK_FALSE;
  }
};

VulkanContext::VulkanContext(const ContextOptions& options) : s_(std::make_unique<State>()) {
  State& s = *s_;
  s.validation = options.validation;
  if (s.validation && !layer_present(kValidationLayer))
    throw VulkanError(std::string("the Vulkan validation layer ") + kValidationLayer +
                      " was asked for (HABUFFER_VK_VALIDATION=1) and is not installed (Debian vulkan-validationlayers)");
  VkDebugUtilsMessengerCreateInfoEXT messenger{};
  messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &State::on_message;
  messenger.pUserData = &s;
  s.instance = make_instance(s.validation, &messenger);
  if (s.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(s.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr) throw VulkanError("the validation layer offers no VK_EXT_debug_utils");
    check(create(s.instance, &messenger, nullptr, &s.messenger), "creating the validation messenger");
  }

  const auto devices = physical_devices(s.instance);
  std::vector<VulkanInfo> infos;
  for (std::uint32_t i = 0; i < devices.size(); ++i) infos.push_back(usable_info(devices[i], i));
  if (infos.empty()) throw VulkanError("no Vulkan device (lavapipe: Debian mesa-vulkan-drivers)");
  const VulkanInfo* chosen = nullptr;
  const DeviceChoice& want = options.device;
  if (want.index) {
    if (*want.index >= infos.size())
      throw VulkanError(want.str() + " (HABUFFER_VK_DEVICE) is not among the Vulkan devices: " + device_list(infos));
    chosen = &infos[*want.index];
  } else if (!want.name.empty()) {
    for (const VulkanInfo& i : infos)
      if (lower(i.name).find(lower(want.name)) != std::string::npos) {
        chosen = &i;
        break;
      }
    if (chosen == nullptr)
      throw VulkanError(want.str() + " (HABUFFER_VK_DEVICE) matches none of the Vulkan devices: " + device_list(infos));
  } else {
    for (const VulkanInfo& i : infos)
      if (i.unusable.empty() && (chosen == nullptr || preference(i) < preference(*chosen))) chosen = &i;
    if (chosen == nullptr)
      throw VulkanError("no usable Vulkan device: " + infos.front().name + ": " + infos.front().unusable);
  }
  if (!chosen->unusable.empty())
    throw VulkanError("Vulkan device " + chosen->name + " cannot run the library: " + chosen->unusable);
  s.info = *chosen;
  s.physical = devices[chosen->index];
  s.family = *universal_family(s.physical);

  // The features the library uses, each only where the device has it.
  VkPhysicalDeviceVulkan12Features v12{};
  v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  v12.shaderBufferInt64Atomics = s.info.buffer_int64_atomics ? VK_TRUE : VK_FALSE;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &v12;
  features.features.shaderInt64 = s.info.shader_int64 ? VK_TRUE : VK_FALSE;
  features.features.fragmentStoresAndAtomics = VK_TRUE;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = s.family;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{};
  dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  dci.pNext = &features;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &queue;
  check(vkCreateDevice(s.physical, &dci, nullptr, &s.device), ("creating a device on " + s.info.name).c_str());
  vkGetDeviceQueue(s.device, s.family, 0, &s.queue);
  s.make_pool();
  check_messages("creating the Vulkan device");
}

VulkanContext::VulkanContext(const HostDevice& host) : s_(std::make_unique<State>()) {
  State& s = *s_;
  if (host.instance == VK_NULL_HANDLE || host.physical_device == VK_NULL_HANDLE || host.device == VK_NULL_HANDLE ||
      host.queue == VK_NULL_HANDLE)
    throw VulkanError("HostDevice: the instance, physical device, device and queue must all be given");
  const auto devices = physical_devices(host.instance);
  const auto found = std::find(devices.begin(), devices.end(), host.physical_device);
  if (found == devices.end())
    throw VulkanError("HostDevice: the physical device is not one of the instance's " +
                      std::to_string(devices.size()) + " devices");
  s.info = query_vulkan_info(host.physical_device, static_cast<std::uint32_t>(found - devices.begin()));
  if (s.info.api < VK_API_VERSION_1_2)
    throw VulkanError("the host's device " + s.info.name + " is Vulkan " + s.info.api_version +
                      " (the library needs 1.2)");
  std::uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &families, props.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  if (host.queue_family >= families || (props[host.queue_family].queueFlags & need) != need)
    throw VulkanError("HostDevice: queue family " + std::to_string(host.queue_family) + " of " + s.info.name +
                      " does not run both graphics and compute");
  if (!host.fragment_stores_and_atomics)
    throw VulkanError("the host's device was made without fragmentStoresAndAtomics, which a gather's fragment "
                      "shaders need to write buffers: enable it at vkCreateDevice");
  // What the host enabled, not what the device offers, decides the modes.
  s.info.shader_int64 = s.info.shader_int64 && host.shader_int64;
  s.info.buffer_int64_atomics = s.info.buffer_int64_atomics && host.buffer_int64_atomics && s.info.shader_int64;
  s.info.unusable.clear();
  s.instance = host.instance;
  s.physical = host.physical_device;
  s.device = host.device;
  s.queue = host.queue;
  s.family = host.queue_family;
  s.adopted = true;
  s.make_pool();
}

VulkanContext::~VulkanContext() = default;

VkInstance VulkanContext::instance() const { return s_->instance; }
VkPhysicalDevice VulkanContext::physical_device() const { return s_->physical; }
VkDevice VulkanContext::device() const { return s_->device; }
VkQueue VulkanContext::queue() const { return s_->queue; }
std::uint32_t VulkanContext::queue_family() const { return s_->family; }
const VulkanInfo& VulkanContext::info() const { return s_->info; }
bool VulkanContext::validation() const { return s_->validation; }

void VulkanContext::submit_and_wait(const std::function<void(VkCommandBuffer)>& record, const char* what,
                                    std::uint64_t timeout_ms) const {
  const State& s = *s_;
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = s.pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(s.device, &ai, &cmd), what);
  VkFence fence = VK_NULL_HANDLE;
  const auto release = [&] {
    if (fence != VK_NULL_HANDLE) vkDestroyFence(s.device, fence, nullptr);
    vkFreeCommandBuffers(s.device, s.pool, 1, &cmd);
  };
  try {
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), what);
    record(cmd);
    check(vkEndCommandBuffer(cmd), what);
    check_messages(what);  // commands the layer refused never reach the driver
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check(vkCreateFence(s.device, &fi, nullptr, &fence), what);
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(s.queue, 1, &si, fence), what);
    const VkResult r = vkWaitForFences(s.device, 1, &fence, VK_TRUE, timeout_ms * 1000000ull);
    if (r == VK_TIMEOUT) {
      vkQueueWaitIdle(s.queue);  // the buffers it uses outlive it (only this queue: a host's others are its own)
      throw VulkanError(std::string(what) + ": not done after " + std::to_string(timeout_ms / 1000) + " s");
    }
    check(r, what);
  } catch (...) {
    if (cmd != VK_NULL_HANDLE) vkQueueWaitIdle(s.queue);
    release();
    throw;
  }
  release();
  check_messages(what);
}

std::vector<std::string> VulkanContext::take_messages() const {
  const std::lock_guard lock(s_->mutex);
  return std::exchange(s_->messages, {});
}

void VulkanContext::check_messages(const char* where) const {
  const std::vector<std::string> messages = take_messages();
  if (messages.empty()) return;
  std::string more = messages.size() > 1 ? " (and " + std::to_string(messages.size() - 1) + " more)" : "";
  throw VulkanError(std::string(where) + ": " + messages.front() + more);
}

}  // namespace habuffer::vk
