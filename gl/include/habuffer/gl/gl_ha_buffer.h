// The HA-buffer on the GPU: its table, max-age table and offsets in shader
// storage buffers, and the paper's per-frame machinery around a host's gather
// pass: the clear pass that counts the previous frame's records under an
// occlusion query into a query buffer, adaptive sizing of SPEC 8 from that
// count read one frame later without a stall (offsets regenerated for every
// new size), the in-frame outcome
// tallies, lossless regathering, the capture mode, the resolve pass, and
// GPU timers. Works in whatever OpenGL 4.5 core context is current (it never
// creates or assumes one) and restores the GL state it touches.
//
// Host use: compile fragment shaders from module_source(ShaderStage::Fragment)
// followed by code that calls ha_insert(pixel, depth, rgba); each frame call
// frame([&] { draw the scene }) and then resolve(background) into the bound
// framebuffer.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/buffer_config.h"
#include "habuffer/fragment.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/lossless_build.h"
#include "habuffer/offset_sequence.h"
#include "habuffer/resize_policy.h"

namespace habuffer::gl {

struct GlFrameOptions {
  bool adaptive = false;  // resize by `policy` from the previous frame's count (SPEC 8)
  ResizePolicy policy;    // also the growth step of lossless mode
  std::uint32_t max_attempts = 1;  // above 1: lossless mode, gather again into a grown table on failure
  std::uint32_t lock_spin_limit = HA_DEFAULT_LOCK_SPIN_LIMIT;  // emulated64: attempts before a call is cut short
  // Calls cut short (a lock given up, the driver's loop budget spent: never
  // the table's fault) are deferred with their carried state and resumed by
  // the resume pass, round after round while any remain, at most this many
  // rounds; only calls still cut short after the last round count failed_iter.
  std::uint32_t resume_rounds = 256;
  // First capacity of the two deferred-call buffers (32 bytes a call); grows
  // (and the frame gathers again) on overflow.
  std::uint64_t deferred_capacity = 1u << 12;
  // Gathers repeated into the same table when calls stayed cut short after
  // every resume round, or a driver ended calls without an outcome (nothing
  // to resume), before the frame reports them as failed_iter. Not counted as
  // lossless attempts.
  std::uint32_t cut_short_retries = 3;
  bool capture = false;                 // append every incoming fragment (read_capture())
  bool capture_only = false;            // capture without inserting (the CPU path replays the capture)
  std::uint64_t capture_capacity = 1u << 20;  // first capacity; grows (and the frame regathers) on overflow
  std::uint32_t clear_tile = 0;  // side of the clear pass's tiles; 0: the framebuffer limits
  bool finish_timing = true;     // glFinish after each pass so wall_ms is the pass's whole time
  bool count_writes = false;     // tally slot writes (FrameReport::slot_writes): one more atomic per insert
};

// Time of one pass: wall clock from submission to completion (glFinish when
// GlFrameOptions::finish_timing, else submission only), and the driver's
// GL_TIME_ELAPSED. Use wall_ms on Mesa llvmpipe: its timer queries measure
// command recording, not rasterization (0.2 ms for an 11 ms gather here).
struct PassTiming {
  double wall_ms = 0.0;
  double gpu_ms = 0.0;
};

struct FrameReport {
  std::uint64_t index = 0;  // frames since construction
  Extent table;             // the table this frame was gathered into
  bool resized = false;     // adaptive sizing changed the table before the gather
  // Whether this frame began with the clear pass (every frame after one that
  // gathered); its occlusion count goes to a query buffer and is read at the
  // next frame's start, one frame late, without a stall (SPEC 8).
  bool cleared = false;
  // The count read at this frame's start: the records the previous frame's
  // clear pass found (those of the frame before it), in `counted_table`;
  // none on the first two frames. Adaptive sizing decides from it when
  // counted_table is still the table (a table resized since then is not
  // judged by a count it did not hold).
  std::optional<std::uint64_t> counted_stored;
  Extent counted_table;
  Counters counters;                   // of the final gather
  std::vector<BuildAttempt> attempts;  // every gather of lossless mode, in order
  // Insert calls cut short by something other than the table (an emulated64
  // lock given up, the driver's loop budget spent) and resumed by the resume
  // pass, summed over its rounds (a call cut twice counts twice).
  std::uint64_t deferred = 0;
  std::uint32_t resume_rounds = 0;  // resume passes run in the final gather
  // Calls of the final gather that never ended: still cut short after the
  // last resume round, or ended by the driver without an outcome (counted
  // failed_iter; lossless mode gathers them again into the same table).
  std::uint64_t cut_short = 0;
  std::uint64_t slot_writes = 0;    // with count_writes: slot raises, evicted records included
  std::uint32_t cut_short_retries = 0;  // gathers repeated because calls were cut short
  std::uint32_t deferred_regathers = 0;  // gathers repeated because the deferred-call buffer overflowed
  bool resize_limited = false;      // adaptive sizing wanted a table beyond this context's limits
  bool growth_limited = false;      // lossless mode stopped: the next table would exceed the limits
  std::uint32_t capture_regathers = 0;  // gathers repeated because the capture buffer overflowed
  std::uint64_t captured = 0;           // fragments in the capture buffer
  PassTiming clear;   // the clear pass (zero on the first frame)
  PassTiming gather;  // the final gather, its resume rounds included
  [[nodiscard]] bool lossless() const { return counters.failures() == 0; }
};

class GlHaBuffer {
 public:
  // Throws std::invalid_argument for a bad config, GlError when the mode cannot
  // hold the layout, the context lacks what the mode needs, or a buffer would
  // exceed the context's limits (the message names the sizes).
  GlHaBuffer(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlFrameOptions& options = {},
             const GlBindings& bindings = {});
  ~GlHaBuffer();
  GlHaBuffer(const GlHaBuffer&) = delete;
  GlHaBuffer& operator=(const GlHaBuffer&) = delete;

  [[nodiscard]] const BufferConfig& config() const { return config_; }  // config().table: the current table
  [[nodiscard]] Extent table() const { return config_.table; }
  [[nodiscard]] AtomicMode mode() const { return mode_; }
  [[nodiscard]] const GlBindings& bindings() const { return bindings_; }
  [[nodiscard]] const OffsetSequence& offsets() const { return offsets_; }
  [[nodiscard]] const GlFrameOptions& options() const { return options_; }

  // The GLSL module for this buffer's atomic mode and binding points.
  [[nodiscard]] std::string module_source(ShaderStage stage, std::string_view header = {}) const;

  // Sets the table for the next frame (at least the screen; offsets
  // regenerated), e.g. from a host's own estimate before the first frame.
  // Throws std::invalid_argument or GlError (beyond the context's limits).
  void resize(Extent table);

  // Binds our buffers to their points, leaving the generic
  // GL_SHADER_STORAGE_BUFFER and GL_UNIFORM_BUFFER bindings as they were
  // (frame() does this around the gather; a host binding them itself
  // restores its own indexed bindings afterwards).
  void bind() const;

  // One frame around `gather`, which draws or dispatches shaders calling
  // ha_insert with our buffers bound, in the GL state the host had when it
  // called frame() (restored before every gather and after the frame).
  // `calls`, when the host can tell, returns how many ha_insert calls the
  // gather made: calls a driver ended without an outcome (llvmpipe's loop
  // budget can stop a SIMD group's lanes) are then counted as failed_iter
  // and cut short, and retried like the others, so nothing goes uncounted.
  FrameReport frame(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls = {});

  // Composites every screen pixel over `background` into the framebuffer
  // bound at the call, at viewport (0, 0, screen). With a background texture
  // (2D, at least the screen), each pixel's background is its texel instead.
  PassTiming resolve(glm::vec3 background, unsigned background_texture = 0);

  // Runs the counting pass without clearing: the records in the table, by
  // occlusion query.
  std::uint64_t count_stored();

  // Slots widened to 64 bits (L32 records in the low half), row-major.
  [[nodiscard]] std::vector<std::uint64_t> read_table() const;
  [[nodiscard]] std::vector<std::uint32_t> read_max_age() const;
  // The fragments the last frame captured, in arrival order.
  [[nodiscard]] std::vector<Fragment> read_capture() const;
  [[nodiscard]] std::uint64_t memory_bytes() const;

 private:
  struct Gpu;
  // Fresh zeroed table (and locks); offsets regenerated for it unless new_offsets is false.
  void allocate_table(Extent table, bool new_offsets = true);
  void write_params() const;
  void reset_frame_state() const;
  void grow_capture(std::uint64_t needed);
  void grow_deferred(std::uint64_t needed);
  // The clear pass; with `later`, its count goes to the query buffer (read
  // by read_pending_count() next frame) and the return value is 0.
  std::uint64_t clear_pass(bool writes, PassTiming* timing, bool later = false);
  [[nodiscard]] std::uint64_t read_pending_count() const;
  // The six outcome tallies and the slot writes.
  [[nodiscard]] std::pair<Counters, std::uint64_t> read_counters() const;
  // Resume rounds while deferred calls remain (at most resume_rounds): returns
  // the calls still deferred after the last round; none are run when the
  // gather deferred more than the buffer holds (deferred_overflow_).
  std::uint64_t resume_deferred(FrameReport& report);
  // Why `table` cannot be allocated here (slot indices, buffer size), or empty.
  [[nodiscard]] std::string table_limit(Extent table) const;
  void run_gather(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls,
                  FrameReport& report);
  [[nodiscard]] std::uint64_t read_capture_count() const;
  [[nodiscard]] std::uint64_t read_deferred_count(int which) const;

  BufferConfig config_;
  OffsetSource source_;
  OffsetSequence offsets_;
  AtomicMode mode_;
  GlFrameOptions options_;
  GlBindings bindings_;
  std::uint32_t cells_ = 0;
  std::uint64_t capture_capacity_ = 0;
  std::uint64_t deferred_capacity_ = 0;
  std::uint64_t deferred_overflow_ = 0;  // calls the last gather deferred, when more than the buffer held
  std::uint64_t frames_ = 0;
  bool holds_frame_ = false;  // the table holds a gathered frame the next clear pass must count
  std::optional<Extent> pending_count_table_;  // the table a count in the query buffer was measured in
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
