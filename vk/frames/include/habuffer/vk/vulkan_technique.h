/// @file
/// A technique's Vulkan part (techniques/NAME/vk): the buffers of one
/// container on a device, its parameters, what a gather starts from, and
/// the read-back into the CPU container of the same configuration, so a
/// Vulkan build is compared with the CPU's record for record.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/atomic_mode.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/technique.h"
#include "habuffer/technique_params.h"
#include "habuffer/vk/compute_pipeline.h"
#include "habuffer/vk/vulkan_context.h"

namespace habuffer::vk {

/// One container of a technique on a Vulkan device (its configuration
/// fixed: lossless growth makes a new one).
class VulkanTechnique {
 public:
  virtual ~VulkanTechnique() = default;
  VulkanTechnique(const VulkanTechnique&) = delete;
  VulkanTechnique& operator=(const VulkanTechnique&) = delete;

  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  [[nodiscard]] AtomicMode mode() const { return mode_; }

  /// Whether a sort pass follows the gather (the technique's descriptor:
  /// not sorted on insert).
  [[nodiscard]] bool sorts_after_gather() const;
  /// Whether its insert calls may be cut short and deferred to the resume
  /// pass (emulated64's locks: the HA-buffer and the k-buffer).
  [[nodiscard]] virtual bool defers_calls() const { return false; }
  /// Reads what it needs of a gather's counter words (the pool techniques:
  /// the nodes asked for), before read_back.
  virtual void gathered(std::span<const std::uint32_t> counter_words) { (void)counter_words; }
  /// Its fields of the parameter block (the frame writes the frame's).
  virtual void write_params(ParamBlock& p) const = 0;
  /// Its buffers at their points of vulkan_bindings(): its own (1-3), its
  /// saturation image where it has one.
  [[nodiscard]] virtual std::vector<BoundBuffer> buffers() const = 0;
  /// Records what empties the container before a gather.
  virtual void record_clear(VkCommandBuffer cmd) const = 0;
  /// Whether a gather runs twice: first a fill gather (the parameter
  /// block's gather phase HABUFFER_PHASE_FILL: nothing inserted or counted),
  /// then its fill pass (fill_pass_compute), then the insert gather (the k-buffer with its
  /// occupancy map). False: one insert gather.
  [[nodiscard]] virtual bool fills_before_insert() const { return false; }
  /// The compute pass between the fill gather and the insert gather (one
  /// invocation per pixel, 8x8 groups) as module text with `defines`: the
  /// builder compiles it once per technique and mode and records it with
  /// the gather's buffers. Called only where fills_before_insert().
  [[nodiscard]] virtual std::string fill_pass_compute(std::string_view defines) const {
    (void)defines;
    return {};
  }
  /// Records it could hold.
  [[nodiscard]] virtual std::uint64_t capacity() const = 0;
  /// The CPU container of the same configuration holding what the device's does.
  [[nodiscard]] virtual std::unique_ptr<FragmentBuffer> read_back() const = 0;

 protected:
  VulkanTechnique(const VulkanContext& context, TechniqueConfig config, AtomicMode mode)
      : context_(context), config_(std::move(config)), mode_(mode) {}
  const VulkanContext& context_;
  TechniqueConfig config_;
  AtomicMode mode_;
};

/// The bytes of emulated64's lock words for `slots` 64-bit slots (one lock
/// per 2^HABUFFER_LOCK_SHIFT slots); 4 in the native modes (bound, never
/// read).
std::uint64_t emulated64_lock_bytes(AtomicMode mode, std::uint64_t slots);

/// Throws VulkanError unless `mode` holds `layout`'s records and the
/// context's device can run it (naming the feature it lacks).
void check_atomic_mode(const VulkanContext& context, AtomicMode mode, Layout layout);

}  // namespace habuffer::vk
