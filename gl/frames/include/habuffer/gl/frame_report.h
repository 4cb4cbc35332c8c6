/// @file
/// What a GPU frame is asked to do (GlFrameOptions) and what it reports
/// (FrameReport), for every technique.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
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

/// When the frame driver reads a frame's outcome (its counters, the calls
/// its resume rounds left, its GPU times) back to the CPU; what each mode
/// guarantees and what a frame costs in it: docs/embedding.md, "What a
/// frame waits for".
enum class Readback : std::uint8_t {
  /// Never waits for the GPU: the frame's counters are copied on the GPU
  /// into a ring of readback buffers behind a fence and read once the fence
  /// has signalled, one or more frames later (FrameReport::completed); the
  /// GPU times come from timestamp queries read then; no glFinish. Sizing
  /// decides from the latest complete count, once it arrives. A frame is
  /// gathered once (no lossless regather: a jump loses fragments in the
  /// frames before its count arrives, each loss counted in its late report),
  /// and the counting gather of an automatic container's first frame (and
  /// after resize_screen or request_recount) is its only wait.
  Deferred,
  /// Waits for every frame's counters (a read-back after the gather): exact
  /// per-frame reports, lossless regathers (max_attempts above 1), capture.
  Immediate,
};

/// "deferred" or "immediate".
std::string_view to_string(Readback readback);

struct FrameReport;
/// What `report`'s last gather asked for (its records needed, the lists'
/// nodes, the arrays' deepest pixel): what lossless growth and adaptive
/// sizing size the container by.
GrowthNeed growth_need(const FrameReport& report);

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
  /// fragments gathered again into a container sized for what the failed
  /// gather counted (ResizePolicy::grown: any jump in one regather, two
  /// where the counted size still fails). Unset: 1 for a container of a
  /// given size or a Deferred readback, kAutomaticAttempts for one sized
  /// automatically with an Immediate readback (lossless from its first
  /// frame). Above 1 needs Readback::Immediate. The driver's options() hold
  /// the resolved count.
  std::optional<std::uint32_t> max_attempts;
  /// The attempts of an automatically sized container when max_attempts is unset.
  static constexpr std::uint32_t kAutomaticAttempts = 16;
  /// When the frame's outcome is read (Readback). Unset: Immediate, which
  /// every existing host gets unchanged; an engine that must never wait
  /// sets Deferred. The driver's options() hold the resolved mode.
  std::optional<Readback> readback;
  /// Lossless mode's time budget: no regather starts once the frame's
  /// attempts have taken this many milliseconds (wall); the frame then keeps
  /// its last gather, lossy, with FrameReport::budget_stopped. 0: none.
  double attempt_budget_ms = 0.0;
  /// Lossless mode's growth budget: no regather grows the container beyond
  /// this factor of its capacity at the frame's start (FrameReport::
  /// budget_stopped as above). 0: none (the context's limits only).
  double growth_budget = 0.0;
  std::uint32_t lock_spin_limit = HABUFFER_DEFAULT_LOCK_SPIN_LIMIT;  ///< emulated64: attempts before a call is cut short
  /// Calls cut short (a lock given up, the driver's loop budget spent: never
  /// the table's fault) are deferred with their carried state and resumed by
  /// the resume pass, round after round while any remain, at most this many
  /// rounds; only calls still cut short after the last round count failed_iter.
  std::uint32_t resume_rounds = 256;
  /// Readback::Deferred: the most resume rounds a frame dispatches without
  /// reading a count (each round reads its calls' count on the GPU; a round
  /// with none is an empty dispatch). The driver dispatches twice the rounds
  /// recent frames needed (all of these, when calls were left), at least
  /// one; calls still cut short after the last count failed_iter in the
  /// frame's late report.
  std::uint32_t late_resume_rounds = 8;
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
  /// time and nothing queued before it. Unset: on with Readback::Immediate;
  /// a Deferred readback never waits (no finish, GPU times read late).
  std::optional<bool> finish_timing;
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

/// The count a sizing decision read: the latest complete frame's.
struct SizingCount {
  std::uint64_t frame = 0;    ///< the frame it was counted in (FrameReport::index)
  std::uint64_t records = 0;  ///< records that frame asked to keep (Counters::records_needed)
  std::uint64_t nodes = 0;    ///< pool techniques: the nodes it asked for, dropped ones included
};

/// What one GlFrameDriver::frame did: sizes, outcome tallies, gathers repeated,
/// and the time of each pass.
struct FrameReport {
  std::uint64_t index = 0;  ///< frames since construction
  /// Whether the outcome below (counters, attempts, GPU times, the
  /// technique's counts) is this frame's: always with Readback::Immediate;
  /// with Deferred, only in the reports of `completed` (frame() returns the
  /// submitted frame's sizes, its outcome arrives in a later frame's report).
  bool complete = true;
  /// Readback::Deferred: the reports of earlier frames whose outcome arrived
  /// since the last frame() (oldest first, each complete), read without a
  /// wait; GlFrameDriver::finish_reports() waits for the rest.
  std::vector<FrameReport> completed;
  /// The count adaptive sizing decided from at this frame's start (the
  /// latest complete frame's, each count read once), when a new one had
  /// arrived: ResizePolicy::next of it (the table or pool for its records
  /// at the middle of the band when its load left the band).
  std::optional<SizingCount> sized_by;
  /// Lossless mode stopped before the frame was lossless because the next
  /// regather would have passed GlFrameOptions::attempt_budget_ms or
  /// growth_budget (the last gather's losses are counted as always).
  bool budget_stopped = false;
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
  /// next frame's start, one frame late (SPEC 8; Readback::Immediate only).
  bool cleared = false;
  /// The count read at this frame's start (Readback::Immediate): the records
  /// the previous frame's clear pass found (those of the frame before it),
  /// in `counted_table`; none on the first two frames. Informative: adaptive
  /// sizing decides from the outcome counters (sized_by), which also count
  /// what an overflowing frame failed to store.
  std::optional<std::uint64_t> counted_stored;
  Extent counted_table;  ///< the table counted_stored was measured in
  Counters counters;                   ///< of the final gather
  /// Every gather of lossless mode, in order: its size, counters, the count
  /// it was sized for (a regather's: the previous gather's records needed)
  /// and its wall time.
  std::vector<BuildAttempt> attempts;
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
  /// Lossless mode stopped because the host's GrowthCheck said growing
  /// cannot help (a pixel deeper than any table holds); the gather's losses
  /// are counted as always.
  bool growth_refused = false;
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
  /// Calls of the final gather counted but not inserted after its first
  /// failure: an HA-buffer's lossless attempt that a regather was to follow
  /// stops inserting there (it only needs its count), and the calls after
  /// count failed_iter of that attempt (0 when the frame ended lossless).
  std::uint64_t skipped = 0;
  /// Whether the final gather lost nothing: no failures in its counters and
  /// no fragment off the screen.
  [[nodiscard]] bool lossless() const { return counters.failures() == 0 && off_screen == 0; }
};

}  // namespace habuffer::gl
