/// @file
/// The Vulkan path for a host's renderer: frames recorded into the host's
/// own command buffer. Around the host's gather (its render pass, its
/// pipeline, its fragment shaders built from module_source() calling
/// habuffer_insert) the driver records what every frame needs, in order:
///
///   1. the parameter block (vkCmdUpdateBuffer), the container's clear and
///      the counters' zeroing, behind a barrier from the previous frame's
///      reads (transfer and compute writes before fragment and compute use);
///   2. the host's gather, called back with the command buffer: it binds the
///      frame's descriptor set (bind()) at set 0 of its pipeline layout
///      (set_layout()); a technique that fills first (the k-buffer's
///      occupancy map) has it called twice, its count pass between;
///   3. a barrier (fragment writes before compute and transfer), the sort
///      pass where the technique sorts after the gather;
///   4. the counters copied into the frame's read-back slot, a barrier that
///      makes the copy available to the host, and the slot's event set
///      (after every earlier command): the frame's report arrives in
///      collect_reports() once the host's submission has run, without any
///      wait;
///   5. timestamps around each step, where the queue family has them.
///
/// record_resolve() then composites every pixel's list over the host's
/// image in place (a compute pass; the image moved to GENERAL and back to
/// the layout the host names). Nothing else of the host's state is touched:
/// the driver binds its own compute pipelines and sets outside the host's
/// render pass, so the host rebinds its own after record_frame and
/// record_resolve (Vulkan has no state to restore across a command buffer).
///
/// Sizing (SPEC 8), across frames, never waiting on the host's frames: each
/// complete report sizes the next frame recorded by the policy
/// (ResizePolicy's band, 80/30 by default; a frame that dropped records
/// grows the next one to hold all it was asked to keep, any jump in one
/// step), the old container kept until every frame recorded with it has
/// run and one frame more (the frame after it sets its event only once all
/// earlier commands, the host's too, are done). An automatic container (no table, no pool) starts at the screen's
/// table or the policy's pool for one fragment a pixel, and is sized by its
/// first frame's report; or before its first frame by size_for() (a host
/// that counted its fragments), or by a counting gather
/// (VulkanFrameOptions::count_first_frame: the host's gather recorded into
/// the driver's own command buffer and waited for, once and after each
/// resize_screen; for a gather that stands alone: its render pass loads no
/// attachment the frame's earlier commands write). A given size adapts only
/// with VulkanFrameOptions::adaptive. Every insert call is counted (SPEC
/// invariant 1); a frame that dropped some says so in its report.
///
/// Atomic modes: native64 and native32. emulated64 (a device without 64-bit
/// buffer atomics) needs resume rounds read between passes, which a command
/// buffer the host submits cannot hold: refused in one line.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "habuffer/atomic_mode.h"
#include "habuffer/fragment.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/offset_source.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique.h"
#include "habuffer/vk/vulkan_context.h"

namespace habuffer::vk {

/// How a VulkanFrameDriver runs its frames.
struct VulkanFrameOptions {
  /// A container of a given size adapts by `policy` too (an automatic one always does).
  bool adaptive = false;
  /// An automatic container's first frame is sized by a counting gather
  /// (see the file comment: the gather must stand alone); false: its first
  /// report sizes the frames after it.
  bool count_first_frame = false;
  ResizePolicy policy;  ///< the band (80/30) and the counted size's target load
  /// GPU times from timestamp queries, where the queue family writes them.
  bool timestamps = true;
  /// Frames recorded whose reports have not arrived (the host submits them
  /// later, or has not yet): a frame beyond them is refused in one line.
  std::uint32_t max_frames_in_flight = 8;
};

/// A host's colour image for record_resolve: its pixels are the background
/// each list is composited over, in place.
struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  /// A 2D view of its first mip level and layer; the image was made with
  /// VK_IMAGE_USAGE_STORAGE_BIT.
  VkImageView view = VK_NULL_HANDLE;
  /// R8G8B8A8_UNORM, R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT.
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent size;  ///< its width and height: the screen's
  /// Its layout when the resolve runs, and again after it (not UNDEFINED:
  /// its content is the background).
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

/// What one recorded frame did, complete once its submission has run.
struct VulkanFrameReport {
  std::uint64_t index = 0;        ///< frames recorded since construction
  TechniqueConfig config;         ///< the container it was gathered into
  std::uint64_t capacity = 0;     ///< records that container holds
  Counters counters;              ///< every insert call's outcome (SPEC invariant 1)
  /// Calls the driver ended without an outcome (a software device's loop
  /// budget), counted in `counters` as failed_iter.
  std::uint64_t ended_by_driver = 0;
  /// The fragments that sized this frame's container before it: a counting
  /// gather's (count_first_frame) or size_for's.
  std::optional<std::uint64_t> counted_fragments;
  /// The frame whose count sized this one's container, where it was made anew for it.
  std::optional<std::uint64_t> sized_by_frame;
  bool resized = false;         ///< its container was made anew (adaptive sizing, the count)
  bool resize_limited = false;  ///< the size wanted exceeds the device's limits: the largest kept
  double clear_ms = 0.0;        ///< GPU times from timestamps (0 without them)
  double gather_ms = 0.0;
  double sort_ms = 0.0;
  double resolve_ms = 0.0;      ///< where record_resolve followed the frame
  /// Whether every call stored or merged its record.
  [[nodiscard]] bool lossless() const { return counters.failures() == 0; }
};

/// Frames of one technique on a host's device, recorded into the host's
/// command buffers (see the file comment). Not copyable; the context must
/// outlive it.
class VulkanFrameDriver {
 public:
  /// The host's gather: records its render pass into `cmd`, its pipeline's
  /// layout with set_layout() at set 0, calling bind() after binding its
  /// pipeline.
  using Gather = std::function<void(VkCommandBuffer cmd)>;

  /// Throws std::invalid_argument for the configuration's or the options'
  /// rules, VulkanError for a technique the Vulkan path does not run, a mode
  /// the device cannot run (naming the feature), emulated64, or a
  /// multisampled screen: each one line, before any device work.
  VulkanFrameDriver(const VulkanContext& context, const TechniqueConfig& config, const OffsetSource& offsets,
                    const VulkanFrameOptions& options = {});
  /// Waits (10 s at most) for the frames still in flight, then for the
  /// context's queue (the host's command buffers may hold commands after a
  /// frame's last event that use the driver's objects), then frees
  /// everything. The host must not submit to that queue from another thread
  /// meanwhile.
  ~VulkanFrameDriver();
  VulkanFrameDriver(const VulkanFrameDriver&) = delete;
  VulkanFrameDriver& operator=(const VulkanFrameDriver&) = delete;

  [[nodiscard]] AtomicMode mode() const;
  [[nodiscard]] Extent screen() const;
  /// The configuration of the container the next frame gathers into.
  [[nodiscard]] TechniqueConfig config() const;
  [[nodiscard]] const VulkanFrameOptions& options() const;

  /// The GLSL module for the host's fragment shaders (Vulkan GLSL 450: the
  /// mode's #extension lines, `header`, the shared module text with its
  /// buffers at set 0, this driver's fingerprint): the host appends a main()
  /// calling habuffer_insert(pixel, depth, coverage, rgba) and compiles it
  /// (its own compiler, or compile_gather_fragment). A shader of another
  /// driver's module inserts nothing and makes that frame's report throw.
  [[nodiscard]] std::string module_source(std::string_view header = {}) const;
  /// module_source() followed by `main_source`, compiled to SPIR-V for the
  /// fragment stage (libglslang). Throws VulkanError with the compiler's log.
  [[nodiscard]] std::vector<std::uint32_t> compile_gather_fragment(std::string_view main_source) const;
  /// Set 0 of the host's gather pipeline layout: the parameter block at
  /// binding 0 (a uniform buffer), storage buffers at 1-9, visible to the
  /// fragment and compute stages. The host adds its own sets from 1.
  [[nodiscard]] VkDescriptorSetLayout set_layout() const;

  /// Sizes an automatic container for frames of `fragments` fragments
  /// (TechniqueConfig::sized_for: the table at the middle of the policy's
  /// band, a pool at its grow_at use), as a counting gather would: the next
  /// frame gathers into it. std::invalid_argument for a container of a
  /// given size; VulkanError beyond the device's limits.
  void size_for(std::uint64_t fragments);

  /// Binds the frame's set at set 0 of `layout` (graphics): only inside a
  /// gather that record_frame calls (VulkanError otherwise).
  void bind(VkCommandBuffer cmd, VkPipelineLayout layout);

  /// Records one frame into `cmd` (a primary command buffer the host is
  /// recording, outside a render pass): see the file comment. Reads first
  /// the reports that arrived (collect_reports keeps them) and sizes this
  /// frame by the latest. Throws VulkanError when the gather bound no set
  /// (bind()), when more frames than max_frames_in_flight are unread, or
  /// for a validation message of the driver's own submissions.
  void record_frame(VkCommandBuffer cmd, const Gather& gather);

  /// Records the resolve of the last recorded frame into `target` (its size
  /// the screen's, its format one of HostImage's) in `cmd`, after that
  /// frame's commands (the same command buffer or a later submission), then
  /// sets the frame's second event: its report waits for the resolve too.
  /// One resolve a frame. Throws std::invalid_argument naming the format,
  /// size or layout, std::logic_error before any frame or for a second
  /// resolve, VulkanError once the frame's report was read.
  void record_resolve(VkCommandBuffer cmd, const HostImage& target);

  /// The reports of frames whose submissions have run (oldest first), read
  /// without a wait; each once. A frame whose calls came from another
  /// driver's module throws VulkanError; the reports before it stay for the
  /// next call.
  std::vector<VulkanFrameReport> collect_reports();
  /// The same for every frame recorded, waiting for each (at most
  /// `timeout_ms` in all, then VulkanError naming the frames left: a frame
  /// recorded but never submitted never completes).
  std::vector<VulkanFrameReport> finish_reports(std::uint64_t timeout_ms = 10000);
  /// Frames recorded whose reports have not been read.
  [[nodiscard]] std::size_t frames_in_flight() const;
  /// For a host that will not submit command buffers it recorded frames
  /// into (a swapchain out of date): after it made sure none of them is
  /// pending (its queue idle), the frames in flight whose reports have not
  /// arrived are forgotten (their reports never come); those that ran are
  /// kept for collect_reports.
  void forget_frames_in_flight();

  /// The last frame's container read back into the CPU's (after
  /// finish_reports: VulkanError while frames are in flight).
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const;

  /// A window resize: the next frame gathers into a container for `screen`
  /// (an automatic one counted again). Waits for the frames in flight
  /// (their reports kept for collect_reports). std::invalid_argument for an
  /// empty screen or the configuration's rules, and nothing changes.
  void resize_screen(Extent screen);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace habuffer::vk
