/// @file
/// What a GPU frame is asked to do (GlFrameOptions) and what it reports
/// (FrameReport), for every technique.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"
#include "habuffer/gl/light_mapping.h"
#include "habuffer/gl/module_variant.h"
#include "habuffer/lossless_build.h"
#include "habuffer/resize_policy.h"

namespace habuffer::gl {

/// Options of every frame of a GlFrameDriver; its constructor throws
/// std::invalid_argument for bad ones (an invalid policy, max_attempts or
/// lock_spin_limit 0, capture_only without capture).
/// The host's depth convention, which habuffer_insert_here() reads
/// gl_FragCoord.z by (records are always nearest first, SPEC 2).
enum class DepthConvention {
  Standard,  ///< window depth 0 is nearest (GL_LESS / GL_LEQUAL; the default depth range)
  Reversed,  ///< window depth 1 is nearest (reversed-Z: GL_GREATER / GL_GEQUAL, glClipControl zero-to-one)
};

struct GlFrameOptions {
  /// Resize by `policy` from the previous frame's count (SPEC 8): the
  /// HA-buffer's table, the linked lists' node pool (fixed arrays keep K).
  /// A container made without a size (the HA-buffer's table or the pool
  /// not given: GlTechnique::sized_automatically) adapts whatever this says,
  /// after the frame driver sized it from a counting gather before its first
  /// frame; this makes a container of a given size adapt from that size.
  bool adaptive = false;
  ResizePolicy policy;    ///< also the growth step of lossless mode and the counted size's band
  /// Gathers a frame may take: above 1, lossless mode, a frame that dropped
  /// fragments gathered again into a grown container. Unset: 1 for a
  /// container of a given size, kAutomaticAttempts for one sized
  /// automatically (lossless from its first frame). The driver's options()
  /// hold the resolved count.
  std::optional<std::uint32_t> max_attempts;
  /// The attempts of an automatically sized container when max_attempts is unset.
  static constexpr std::uint32_t kAutomaticAttempts = 16;
  std::uint32_t lock_spin_limit = HABUFFER_DEFAULT_LOCK_SPIN_LIMIT;  ///< emulated64: attempts before a call is cut short
  /// Calls cut short (a lock given up, the driver's loop budget spent: never
  /// the table's fault) are deferred with their carried state and resumed by
  /// the resume pass, round after round while any remain, at most this many
  /// rounds; only calls still cut short after the last round count failed_iter.
  std::uint32_t resume_rounds = 256;
  /// First capacity of the two deferred-call buffers (40 bytes a call); grows
  /// (and the frame gathers again) on overflow.
  std::uint64_t deferred_capacity = 1u << 12;
  /// Gathers repeated into the same table when calls stayed cut short after
  /// every resume round, or a driver ended calls without an outcome (nothing
  /// to resume), before the frame reports them as failed_iter. Not counted as
  /// lossless attempts.
  std::uint32_t cut_short_retries = 3;
  bool capture = false;                 ///< append every incoming fragment (read_capture())
  bool capture_only = false;            ///< capture without inserting (the CPU path replays the capture)
  std::uint64_t capture_capacity = 1u << 20;  ///< first capacity; grows (and the frame regathers) on overflow
  std::uint32_t clear_tile = 0;  ///< side of the clear pass's tiles; 0: the framebuffer limits
  /// glFinish before and after each pass, so a pass's wall_ms is its whole
  /// time and nothing queued before it.
  bool finish_timing = true;
  /// The insertion module's compile-time variant (slot-write tally, read-first
  /// loads): in module_source() and every pass of the driver.
  ModuleVariant module;
  /// How habuffer_insert_here() reads gl_FragCoord.z. frame() refuses a depth test
  /// enabled at the call with a function of the other convention (GL_GREATER
  /// or GL_GEQUAL with Standard, GL_LESS or GL_LEQUAL with Reversed), which
  /// would otherwise composite back to front with no error.
  DepthConvention depth = DepthConvention::Standard;
  /// The light this driver gathers a light buffer for (translucent shadows,
  /// light_mapping.h): its records then hold the light's linear depth t,
  /// which GlShadowLookup compares, rather than window depth. The module
  /// gains habuffer_insert_light(colour) and (colour, eye_distance), and
  /// habuffer_insert_here stores t too, from gl_FragCoord.z through the
  /// projection under the clip control and depth range of the frame() call.
  /// Unset: depths are what the host inserts, and habuffer_insert_light does
  /// not compile. The constructor throws std::invalid_argument for a mapping
  /// light_depth_map refuses.
  std::optional<GlLightMapping> light;
};

/// Time of one pass: wall clock from submission to completion (glFinish when
/// GlFrameOptions::finish_timing, else submission only), and the driver's
/// time between two GL_TIMESTAMP queries (never an active GL_TIME_ELAPSED
/// query, which would end or block a host's own). Use wall_ms on Mesa
/// llvmpipe: its timer queries measure command recording, not rasterization.
struct PassTiming {
  double wall_ms = 0.0;  ///< wall clock (ms)
  double gpu_ms = 0.0;   ///< between two GL_TIMESTAMP queries (ms)
};

/// What one GlFrameDriver::frame did: sizes, outcome tallies, gathers repeated,
/// and the time of each pass.
struct FrameReport {
  std::uint64_t index = 0;  ///< frames since construction
  Extent table;             ///< HA-buffer: the table this frame was gathered into
  std::uint64_t capacity = 0;  ///< records the technique could hold in this frame (slots, nodes, layers of every pixel)
  std::uint64_t nodes_requested = 0;  ///< linked lists: nodes the final gather asked for (dropped ones included)
  std::uint32_t most_arrived = 0;     ///< fixed arrays: the most fragments a pixel received, when some pixel overflowed
  bool resized = false;     ///< adaptive sizing changed the table before the gather
  /// Fragments the counting gather found (on-screen insert calls), when this
  /// frame ran one: an automatic container's first frame, and the first
  /// after a resize_screen. The container was sized from it before the gather.
  std::optional<std::uint64_t> counted_fragments;
  /// Whether this context's limits gave the counted container less than the
  /// count asked for (the frame may then drop fragments; lossless growth is
  /// bounded by the same limits).
  bool count_limited = false;
  /// Whether this frame began with the clear pass (every frame after one that
  /// gathered); its occlusion count goes to a query buffer and is read at the
  /// next frame's start, one frame late, without a stall (SPEC 8).
  bool cleared = false;
  /// The count read at this frame's start: the records the previous frame's
  /// clear pass found (those of the frame before it), in `counted_table`;
  /// none on the first two frames. Adaptive sizing decides from it when
  /// counted_table is still the table (a table resized since then is not
  /// judged by a count it did not hold).
  std::optional<std::uint64_t> counted_stored;
  Extent counted_table;  ///< the table counted_stored was measured in
  Counters counters;                   ///< of the final gather
  std::vector<BuildAttempt> attempts;  ///< every gather of lossless mode, in order
  /// Insert calls cut short by something other than the table (an emulated64
  /// lock given up, the driver's loop budget spent) and resumed by the resume
  /// pass, summed over its rounds (a call cut twice counts twice).
  std::uint64_t deferred = 0;
  std::uint32_t resume_rounds = 0;  ///< resume passes run in the final gather
  /// Calls of the final gather that never ended: still cut short after the
  /// last resume round, or ended by the driver without an outcome (counted
  /// failed_iter; lossless mode gathers them again into the same table).
  std::uint64_t cut_short = 0;
  /// Slot raises, evicted records included, when ModuleVariant::count_writes
  /// compiled the tally in; nullopt otherwise (not counted, not zero).
  std::optional<std::uint64_t> slot_writes;
  std::uint32_t cut_short_retries = 0;  ///< gathers repeated because calls were cut short
  std::uint32_t deferred_regathers = 0;  ///< gathers repeated because the deferred-call buffer overflowed
  bool resize_limited = false;      ///< adaptive sizing wanted a table beyond this context's limits
  bool growth_limited = false;      ///< lossless mode stopped: the next table would exceed the limits
  std::uint32_t capture_regathers = 0;  ///< gathers repeated because the capture buffer overflowed
  std::uint64_t captured = 0;           ///< fragments in the capture buffer
  PassTiming clear;   ///< the clear pass (zero on the first frame)
  PassTiming count;   ///< the counting gather and the sizing after it (zero without one)
  /// The buffer resets before the final gather (tallies, the max-age table,
  /// list heads, ...), with finish_timing waited for before the gather's
  /// clock starts: so `gather` spans the gather alone, not work queued before it.
  PassTiming reset;
  PassTiming gather;  ///< the final gather, its resume rounds included (never a read-back)
  PassTiming sort;    ///< linked lists, fixed arrays: the sort pass after the final gather
  /// Insert calls of the final gather whose pixel lay outside the screen
  /// (also in counters.invalid): fragments lost, for instance drawn by a
  /// host whose window grew beyond the screen it configured (resize_screen()).
  std::uint64_t off_screen = 0;
  /// Whether the final gather lost nothing: no failures in its counters and
  /// no fragment off the screen.
  [[nodiscard]] bool lossless() const { return counters.failures() == 0 && off_screen == 0; }
};

}  // namespace habuffer::gl
