/// @file
/// What every Vulkan frame shares, whoever records it (a stream build's
/// compute gather, a host's render-pass gather): the module variant run on
/// a device, the frame's buffers at their binding points, and a gather's
/// counters from its counter words.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "habuffer/atomic_mode.h"
#include "habuffer/counters.h"
#include "habuffer/vk/compute_pipeline.h"
#include "habuffer/vk/vulkan_info.h"
#include "habuffer/vk/vulkan_technique.h"

namespace habuffer::vk {

/// The defines of the module variant the Vulkan path runs for `mode` on a
/// device (the OpenGL path's ModuleVariant::resolved rule: reads first
/// where an atomic is dear), after the device's own (vulkan_device_defines).
std::string frame_variant_defines(AtomicMode mode, const VulkanInfo& info);

/// The frame's own buffers, beside the technique's.
struct FrameBuffers {
  const VulkanBuffer* params = nullptr;    ///< the parameter block (a uniform buffer)
  const VulkanBuffer* counters = nullptr;  ///< the outcome tallies
  const VulkanBuffer* capture = nullptr;   ///< the capture; also bound at every point the technique leaves free
  const VulkanBuffer* stream = nullptr;    ///< a compute entry's fragments, or the resolve's image buffer
  const VulkanBuffer* deferred = nullptr;  ///< emulated64's calls cut short (its header alone otherwise)
};

/// Every binding of vulkan_bindings() for a gather of `t`: its own buffers,
/// the frame's, and the capture buffer at each point `t` leaves free (bound,
/// never written: the module reads a point only where it has its buffer).
std::vector<BoundBuffer> frame_bindings(const VulkanTechnique& t, const FrameBuffers& frame);

/// The parameter block of a gather of `t` in `phase` (HABUFFER_PHASE_*):
/// the screen, the lock spin limit and the technique's fields; the caller
/// adds what is its own (the deferred calls' capacity, a module fingerprint).
ParamBlock frame_params(const VulkanTechnique& t, std::uint32_t phase);

/// A gather's counters from its counter words (HABUFFER_COUNTER_WORDS of
/// striped tallies). Throws VulkanError when calls came from another
/// module than the frame's (HABUFFER_COUNTER_FOREIGN).
Counters counters_from_words(std::span<const std::uint32_t> words);

}  // namespace habuffer::vk
