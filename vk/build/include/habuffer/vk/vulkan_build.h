/// @file
/// A fragment stream built into a technique's container on a Vulkan device
/// through the compute entry every path shares (the fragments in a buffer,
/// one insert call each, in stream order chunk by chunk), the sort pass where
/// the technique has one, lossless mode's regathers by every path's rule, and the container read back into the CPU's: the Vulkan twin
/// of build_technique and build_technique_on_gl.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/fragment.h"
#include "habuffer/lossless_build.h"
#include "habuffer/vk/vulkan_context.h"

namespace habuffer::vk {

/// How a Vulkan build ran.
struct VulkanBuildInfo {
  double build_ms = 0.0;  ///< the upload and every attempt's gather, resume rounds, sort pass and counters (GL's span)
  std::string atomic_mode;       ///< native32, native64, emulated64
  std::string device;            ///< the device's name
  /// Insert calls the driver ended without an outcome (a loop budget),
  /// counted failed_iter as on GL; all attempts.
  std::uint64_t ended_by_driver = 0;
  /// Insert calls cut short and resumed (emulated64), all attempts; a
  /// gather run again after the deferred buffer overflowed counts too.
  std::uint64_t deferred = 0;
  std::uint32_t resume_rounds = 0;  ///< resume passes, all attempts
};

/// `fragments` built on the context's device as build_technique builds them
/// on the CPU (an unset table is the screen; the automatic pool is the
/// CPU's), at most `max_attempts` attempts in lossless mode. Throws
/// std::out_of_range naming a fragment off the screen, VulkanError for a
/// technique the path does not run, a mode the device cannot run, or a
/// validation message.
TechniqueBuild build_technique_on_vulkan(const VulkanContext& context, const TechniqueConfig& config,
                                         const OffsetSource& offsets, std::span<const Fragment> fragments,
                                         const ResizePolicy& policy = {}, std::uint32_t max_attempts = 1,
                                         VulkanBuildInfo* info = nullptr);

/// A build's image (SPEC 7), resolved on the device after its last attempt
/// by the technique's composite (the shared GLSL the OpenGL path's resolve
/// pass runs).
struct VulkanResolve {
  std::span<const glm::vec3> backgrounds;  ///< in: screen.area() colours, row 0 at the bottom
  std::vector<glm::vec4> image;            ///< out: each pixel's list composited over its background
  double resolve_ms = 0.0;                 ///< out: the upload, the pass and the read-back
};

/// Builds streams on one context's device, keeping the pipelines of the
/// last technique and mode (compiled once, not per build): what a host or
/// `render` that builds frame after frame holds. Not copyable; the context
/// must outlive it.
class VulkanStreamBuilder {
 public:
  explicit VulkanStreamBuilder(const VulkanContext& context);
  ~VulkanStreamBuilder();
  VulkanStreamBuilder(const VulkanStreamBuilder&) = delete;
  VulkanStreamBuilder& operator=(const VulkanStreamBuilder&) = delete;

  /// build_technique_on_vulkan's build; with `resolve`, then the last
  /// attempt's container resolved into resolve->image on the device (its
  /// backgrounds checked first: std::invalid_argument naming both sizes).
  TechniqueBuild build(const TechniqueConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                       const ResizePolicy& policy = {}, std::uint32_t max_attempts = 1,
                       VulkanBuildInfo* info = nullptr, VulkanResolve* resolve = nullptr);

 private:
  struct Pipelines;
  const VulkanContext& context_;
  std::unique_ptr<Pipelines> pipelines_;
};

/// build_technique_on_vulkan, then the last attempt's container resolved
/// into `resolve.image` on the device. Throws std::invalid_argument when
/// `resolve.backgrounds` does not hold one colour per pixel (naming both
/// sizes), before any device work.
TechniqueBuild build_and_resolve_on_vulkan(const VulkanContext& context, const TechniqueConfig& config,
                                           const OffsetSource& offsets, std::span<const Fragment> fragments,
                                           VulkanResolve& resolve, const ResizePolicy& policy = {},
                                           std::uint32_t max_attempts = 1, VulkanBuildInfo* info = nullptr);

}  // namespace habuffer::vk
