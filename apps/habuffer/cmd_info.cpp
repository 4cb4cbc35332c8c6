// habuffer info: what this build is and which paths it offers.
#include <algorithm>
#include <cstdio>


#include "cli_args.h"
#include "commands.h"
#include "habuffer/cache_sizes.h"
#include "habuffer/parallel.h"
#include "habuffer/render/image.h"
#include "habuffer/render/voxel_vdb.h"
#include "habuffer/technique.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/gl_technique.h"
#ifdef HABUFFER_WITH_VK
#include <optional>

#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_info.h"
#include "habuffer/vk/vulkan_registry.h"
#endif

namespace habuffer::cli {

const CommandSpec& info_spec() {
  static const CommandSpec spec{"info", {}, "  Version, build type, techniques and the paths this machine offers.\n"};
  return spec;
}

namespace {

#ifdef HABUFFER_WITH_VK
// Atomic modes of `info`'s device: those it runs, and the one L64 gets.
std::string vulkan_modes(const vk::VulkanInfo& info) {
  std::string modes;
  for (AtomicMode m : vk::runnable_atomic_modes(info)) modes += (modes.empty() ? "" : ", ") + to_string(m);
  std::string l64;
  try {
    const auto mode = vk::chosen_atomic_mode(info, Layout::L64);
    l64 = mode ? to_string(*mode) : "none (no shaderInt64)";
    if (mode && atomic_mode_override()) l64 += " (forced by HABUFFER_ATOMIC_MODE)";
  } catch (const vk::VulkanError& e) {
    l64 = std::string("refused: ") + e.what();
  }
  return "atomic modes runnable: " + modes + "; chosen: L32 -> native32, L64 -> " + l64;
}
#endif

// The Vulkan devices, which one the path uses (HABUFFER_VK_DEVICE), what
// each offers; or why there is none.
void print_vulkan() {
#ifdef HABUFFER_WITH_VK
  try {
    const std::vector<vk::VulkanInfo> devices = vk::list_devices();
    std::optional<std::uint32_t> used;
    std::string why_none;
    try {
      vk::ContextOptions options;
      options.validation = false;  // only which device: no layer needed
      used = vk::VulkanContext(options).info().index;
    } catch (const vk::VulkanError& e) {
      why_none = e.what();
    }
    std::printf("  vk: %s (techniques: %s; build-lists, render, bench, sweep and figure frontier with --path vk)\n",
                used ? ("device " + std::to_string(*used) + " used, chosen by " + vk::DeviceChoice::from_environment().str() +
                        " (HABUFFER_VK_DEVICE)").c_str()
                     : ("unavailable: " + why_none).c_str(),
                vk::vulkan_technique_names().c_str());
    for (const vk::VulkanInfo& d : devices) {
      std::printf("    %u: %s (%s), Vulkan %s, driver %s%s\n", d.index, d.name.c_str(), d.type.c_str(),
                  d.api_version.c_str(), d.driver.c_str(), used && *used == d.index ? " [used]" : "");
      if (!d.unusable.empty()) {
        std::printf("      unusable: %s\n", d.unusable.c_str());
        continue;
      }
      std::printf("      shaderInt64: %s; shaderBufferInt64Atomics: %s; fragmentStoresAndAtomics: %s; timestamps: %s\n",
                  d.shader_int64 ? "yes" : "no", d.buffer_int64_atomics ? "yes" : "no",
                  d.fragment_stores ? "yes" : "no", d.timestamps ? "yes" : "no");
      std::printf("      limits: storage binding %llu MiB, compute work groups x %u, framebuffer %ux%u\n",
                  static_cast<unsigned long long>(d.max_storage_range >> 20), d.max_work_groups_x,
                  d.max_framebuffer_width, d.max_framebuffer_height);
      std::printf("      %s\n", vulkan_modes(d).c_str());
    }
  } catch (const vk::VulkanError& e) {
    std::printf("  vk: unavailable: %s\n", e.what());
  }
#else
  std::printf("  vk: not built (HABUFFER_WITH_VULKAN: Debian libvulkan-dev and glslang-dev)\n");
#endif
}

}  // namespace

int run_info(const std::vector<std::string>& argv) {
  if (print_help(argv, info_spec())) return 0;
  const Args args(argv, info_spec());
  std::printf("habuffer %s\n", HABUFFER_VERSION);
  std::printf("build type: %s%s%s\n", HABUFFER_BUILD_TYPE, *HABUFFER_SANITIZE_NAME ? ", sanitizers: " : "",
              HABUFFER_SANITIZE_NAME);
  std::printf("compiler: %s\n", __VERSION__);
  std::printf("techniques: %s (every one on both paths; --technique)\n", technique_names().c_str());
  std::printf("image files: %s\n", image_support().c_str());
  std::printf("voxel files: HAVOXEL1, NRRD, OpenVDB: %s\n", vdb_support().c_str());
  std::printf("paths:\n");
  std::printf("  cpu: available (%s, %u hardware threads; layouts L64 and L32; age bits 4..12)\n",
              parallel_runtime().c_str(), default_concurrency());
  std::printf("    HA-buffer insert order: auto = pixel (bucketed by pixel, nearest first, jump-started; the table of\n"
              "    arrival order; under early cull another conservative schedule) at >= 1 fragment per %llu pixels\n"
              "    and >= %.1f fragments per covered pixel, else arrival; --insert-order\n",
              static_cast<unsigned long long>(kPixelOrderPixelsPerFragment), kPixelOrderMinDepth);
  const CacheSizes& caches = cache_sizes();
  const auto kib = [](std::uint64_t bytes) { return static_cast<unsigned long long>(bytes >> 10); };
  std::printf("    caches (%s): L1d %llu KiB, L2 %llu KiB, L3 %llu KiB; pixel order interleaves %zu pixels a thread\n"
              "    where the table exceeds the L2\n",
              caches.source.c_str(), kib(caches.l1d), kib(caches.l2), kib(caches.l3), kInterleavedPixels);
  try {
    const gl::EglContext context;
    const gl::GlInfo info = gl::query_gl_info();
    std::printf("  gl: available through %s\n", context.description().c_str());
    std::printf("    GL_VENDOR %s, GL_RENDERER %s\n    GL_VERSION %s, GLSL %s\n", info.vendor.c_str(),
                info.renderer.c_str(), info.version.c_str(), info.glsl_version.c_str());
    std::printf("    64-bit shader types (GL_ARB_gpu_shader_int64): %s; 64-bit atomics (GL_NV_shader_atomic_int64): %s\n",
                info.int64_types ? "yes" : "no", info.atomic_int64 ? "yes" : "no");
    std::printf("    limits: SSBO %lld MiB, framebuffer %dx%d, compute work groups x %d\n", info.max_ssbo_bytes >> 20,
                info.max_framebuffer_width, info.max_framebuffer_height, info.max_compute_work_groups_x);
    const gl::MultisampleLimits ms = gl::multisample_limits();
    std::string counts = "1";
    for (std::uint32_t c : ms.counts) counts += ", " + std::to_string(c);
    std::printf("    multisampling (--samples): %s (float images; at most %d by %s)\n", counts.c_str(), ms.largest,
                ms.limited_by.c_str());
    const long long max_slots = std::min<long long>(info.max_ssbo_bytes, 0xFFFFFFFFll * 4);
    std::printf("    largest table: L64 %lld slots, L32 %lld slots (one shader-storage buffer, 32-bit slot indices)\n",
                std::min<long long>(max_slots / 8, 0xFFFFFFFFll), std::min<long long>(max_slots / 4, 0xFFFFFFFFll));
    std::string modes;
    for (gl::AtomicMode m : gl::runnable_atomic_modes(info)) modes += (modes.empty() ? "" : ", ") + gl::to_string(m);
    std::string l64_text;
    try {
      const auto l64 = gl::chosen_atomic_mode(info, Layout::L64);
      l64_text = l64 ? gl::to_string(*l64) : "none (no 64-bit shader types)";
      if (l64 && gl::atomic_mode_override()) l64_text += " (forced by HABUFFER_ATOMIC_MODE)";
    } catch (const gl::GlError& e) {
      l64_text = std::string("refused: ") + e.what();
    }
    std::printf("    atomic modes runnable: %s; chosen: L32 -> native32, L64 -> %s\n", modes.c_str(), l64_text.c_str());
  } catch (const gl::GlError& e) {
    std::printf("  gl: unavailable: %s\n", e.what());
  }
  print_vulkan();
  return 0;
}

}  // namespace habuffer::cli
