#include "vk_build.h"

#include <optional>

#include "cli_args.h"
#include "habuffer/data_error.h"
#include "habuffer/vk/vulkan_build.h"
#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_error.h"

namespace habuffer::cli {

TechniqueBuild build_on_vk(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  try {
    const vk::VulkanContext context;
    vk::VulkanBuildInfo info;
    TechniqueBuild built = vk::build_technique_on_vulkan(context, technique_config(options), options.offsets, fragments,
                                                         options.policy, options.max_attempts, &info);
    timing.build_ms = info.build_ms;
    timing.vk_atomic_mode = info.atomic_mode;
    timing.vk_device = info.device;
    timing.vk_ended_by_driver = info.ended_by_driver;
    timing.vk_deferred = info.deferred;
    timing.vk_resume_rounds = info.resume_rounds;
    return built;
  } catch (const vk::VulkanError& e) {
    throw DataError(std::string("--path vk: ") + e.what());
  }
}

}  // namespace habuffer::cli
