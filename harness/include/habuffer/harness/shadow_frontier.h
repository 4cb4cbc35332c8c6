/// @file
/// The shadow frontier (issue 20): light buffers of every kind built from
/// one light pass's fragments, each scored against the ray-traced reference
/// at the same receivers (habuffer/render/shadow_accuracy.h): RMSE of T vs
/// memory vs build time, for the exact HA-buffer (built on the GPU by the
/// render's light pass, and on the CPU from its captured stream), the
/// HA-buffer with early cull, the k-buffer's k nearest records, and opacity
/// shadow maps of N slices (habuffer/opacity_shadow_map.h).
#pragma once

#include <cstdint>
#include <functional>

#include <glm/vec3.hpp>

#include "habuffer/harness/result_table.h"
#include "habuffer/harness/workload.h"

namespace habuffer::harness {

/// What the frontier runs with.
struct ShadowFrontierSettings {
  Extent size{128, 128};          ///< the view's pixels
  Extent light_size{512, 512};    ///< the light map's pixels
  glm::vec3 light_direction{-0.4f, -1.0f, -0.3f};  ///< a directional light (orthographic)
  std::uint32_t threads = 0;      ///< CPU builds: worker threads, 0 for the default
  std::uint32_t repeats = 3;      ///< CPU builds timed this many times (median)
  std::uint64_t max_receivers = 0;  ///< receivers checked (every k-th); 0: all
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (light buffers done, light buffers)
};

/// The frontier on `scene` (a scene word, not a fragment file). Needs a
/// current OpenGL 4.5 context with 64-bit shader integers. Throws
/// std::invalid_argument for a fragment file or bad settings.
ResultTable run_shadow_frontier(const WorkloadSpec& scene, const ShadowFrontierSettings& settings);

}  // namespace habuffer::harness
