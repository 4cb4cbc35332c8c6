/// @file
/// The GPU path's frame machinery, the same for every technique: around a
/// host's gather pass it restores the host's GL state, writes the parameter
/// block, binds the buffers, tallies every insert call's outcome (SPEC
/// invariant 1 on the GPU), captures the incoming fragments when asked,
/// resumes calls cut short (the HA-buffer's deferred calls), regathers when a
/// capture or deferral buffer overflowed or calls stayed cut short, runs the
/// lossless loop that asks the technique to grow, resolves, and times every
/// pass. The technique (GlTechnique: the HA-buffer's table, linked lists,
/// fixed arrays) owns its buffers and its own passes. Works in whatever
/// OpenGL 4.5 core context is current (it never creates or assumes one).
///
/// Host use: compile fragment shaders from module_source(ShaderStage::Fragment)
/// followed by code that calls habuffer_insert(pixel, depth, rgba); each frame call
/// frame([&] { draw the scene }) and then resolve(background) into the bound
/// framebuffer.
#pragma once

#include <algorithm>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/fragment.h"
#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// Whether a lossless regather may grow the container (GlFrameDriver::frame).
using GrowthCheck = std::function<bool(const FrameReport& failed)>;

/// Runs frames of one technique's container on the GPU (see the file comment);
/// GlHaBuffer is the HA-buffer's.
class GlFrameDriver {
 public:
  /// Throws std::invalid_argument for bad options, GlError when the screen or
  /// a binding point exceeds the context's limits.
  GlFrameDriver(std::unique_ptr<GlTechnique> technique, const GlFrameOptions& options = {});
  /// Deletes the frame's buffers and passes, and the technique with its own.
  virtual ~GlFrameDriver();
  GlFrameDriver(const GlFrameDriver&) = delete;
  GlFrameDriver& operator=(const GlFrameDriver&) = delete;

  /// The technique's container, which the driver owns.
  [[nodiscard]] GlTechnique& technique() { return *technique_; }
  /// The same, read-only.
  [[nodiscard]] const GlTechnique& technique() const { return *technique_; }
  /// The technique's atomic mode.
  [[nodiscard]] AtomicMode mode() const { return technique_->mode(); }
  /// The binding points of every buffer (checked by the constructor).
  [[nodiscard]] const GlBindings& bindings() const { return technique_->bindings(); }
  /// The screen, in pixels.
  [[nodiscard]] Extent screen() const { return technique_->screen(); }
  /// The options every frame runs with (the module variant resolved: ModuleVariant::resolved).
  [[nodiscard]] const GlFrameOptions& options() const { return options_; }
  /// Whether the implementation can end an insert call without an outcome
  /// (its loop budget: GlInfo::software_rasterizer). The driver then counts
  /// the calls of shaders built from module_source() itself
  /// (HABUFFER_COUNTER_CALLS, one atomic per call compiled into the module
  /// only there) and counts calls ended so as failed_iter; a host need not
  /// count its calls (frame()'s `calls` is optional; a host whose shaders
  /// come from the installed GLSL files gives it where it can).
  [[nodiscard]] bool needs_call_count() const { return needs_call_count_; }
  /// Caps the attempts per frame from now on (at least 1): a caller that
  /// knows growth cannot help (a pixel deeper than AMAX) stops it.
  void limit_attempts(std::uint32_t attempts) {
    options_.max_attempts = std::max(1u, std::min(*options_.max_attempts, attempts));
  }
  /// Undoes limit_attempts: the attempts the driver was made with (a host
  /// whose view changed, so growth may help again).
  void restore_attempts() { options_.max_attempts = made_attempts_; }
  /// The attempts per frame the driver was made with (options().max_attempts
  /// before any limit_attempts).
  [[nodiscard]] std::uint32_t made_attempts() const { return made_attempts_; }

  /// Whether the next frame() begins with a counting gather: the container
  /// is sized automatically (GlTechnique::sized_automatically) and has not
  /// been sized for its screen yet (its first frame, the first after a
  /// resize_screen), and no size_for() came first.
  [[nodiscard]] bool counts_next_frame() const { return needs_count_; }
  /// Sizes an automatically sized container for a frame of `fragments`
  /// fragments (TechniqueConfig::sized_for: the table at the middle of the
  /// policy's band, a pool at its grow_at use; the largest this context
  /// holds), as the counting gather does: a host that counted its own
  /// fragments saves that gather. Returns whether this context's limits made
  /// it smaller. Throws std::invalid_argument for a container of a given
  /// size, GlError beyond the GPU path's 32-bit counts.
  bool size_for(std::uint64_t fragments);
  /// The next frame() begins with a counting gather and sizes the container
  /// from it, as the first frame does (counts_next_frame()): for a host
  /// that knows its scene changed at once (a cut, a level load) and wants
  /// that frame sized before it gathers. Throws std::invalid_argument for a
  /// container of a given size.
  void request_recount();

  /// Readback::Deferred: waits (at most 10 s a frame, GlError beyond) for
  /// every frame still in flight and returns their reports, oldest first,
  /// each complete; the sizing count they carry is taken too. Empty with
  /// Readback::Immediate. For tools and tests that want every figure before
  /// they stop, never needed per frame.
  std::vector<FrameReport> finish_reports();
  /// Readback::Deferred: frames whose outcome has not been read yet.
  [[nodiscard]] std::size_t frames_in_flight() const;

  /// A window resize: the technique's screen changed in place
  /// (GlTechnique::resize_screen: every per-pixel buffer made anew, the
  /// HA-buffer's table and the node pool scaled with the screen), and the
  /// parameter block with it. The next frame and resolve cover the new
  /// screen; the last frame's lists are gone. Throws std::invalid_argument
  /// (an empty screen, the configuration's rules) or GlError (this
  /// context's viewport or buffer limits), each one line naming the sizes,
  /// and then leaves everything as it was. Shaders, the capture and the
  /// deferred-call buffers are kept (none depends on the screen).
  void resize_screen(Extent screen);

  /// A light pass's light moved (GlFrameOptions::light): the next frames
  /// store its t. Throws std::invalid_argument for a driver made without a
  /// light (its module has no habuffer_insert_light) or a mapping
  /// light_depth_map refuses, and then changes nothing.
  void set_light(const GlLightMapping& light);

  /// The GLSL module for this technique, atomic mode and binding points,
  /// with this driver's fingerprint (HABUFFER_MODULE_ID): insert calls from
  /// a shader built from another driver's module, whose text differs, insert
  /// nothing and make frame() throw a GlError naming them (detected where
  /// that shader still writes this driver's counters: the same binding points).
  [[nodiscard]] std::string module_source(ShaderStage stage, std::string_view header = {}) const;

  /// Binds our buffers to their points, leaving the generic
  /// GL_SHADER_STORAGE_BUFFER and GL_UNIFORM_BUFFER bindings as they were
  /// (frame() does this around the gather; a host binding them itself
  /// restores its own indexed bindings afterwards).
  void bind() const;

  /// One frame around `gather`, which draws or dispatches shaders calling
  /// habuffer_insert with our buffers bound, in the GL state the host had when it
  /// called frame() (restored before every gather and after the frame).
  /// `calls`, optional, returns how many habuffer_insert calls the gather
  /// made (Readback::Immediate): where needs_call_count() the driver counts
  /// them itself, and a host's count, when given, is used instead. Calls a
  /// driver ended without an outcome (llvmpipe's loop budget can stop a SIMD
  /// group's lanes) are counted as failed_iter and cut short, and retried
  /// like the others, so nothing goes uncounted.
  ///
  /// Readback::Immediate returns the frame's whole report (its counters read
  /// back after the gather: a wait). Readback::Deferred never waits: the
  /// report holds what was known at submission (complete false) and, in
  /// `completed`, the reports of earlier frames whose outcome arrived; a
  /// deferred frame's GL errors and refused calls (another driver's module,
  /// a framebuffer of other samples) throw from the frame() that reads them.
  ///
  /// `may_grow`, optional, is asked before each lossless regather would grow
  /// the container, with the failed gather's report (its counters; the
  /// host's own per-pixel counts of that gather are still in its buffers):
  /// false keeps that gather, lossy, with FrameReport::growth_refused. A
  /// host that counts its fragments per pixel saves growing a table for a
  /// pixel deeper than AMAX, which no table holds (pixel_counted_beyond).
  FrameReport frame(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls = {},
                    const GrowthCheck& may_grow = {});

  /// Composites every screen pixel over `background` into the framebuffer
  /// bound at the call, at viewport (0, 0, screen), replacing its colour:
  /// colour C + T * background and alpha 1 - T (T: the pixel's transmittance).
  /// With a background texture (2D, at least the screen, bound to texture
  /// unit 0 for the pass), each pixel's background is its texel instead.
  PassTiming resolve(glm::vec3 background, unsigned background_texture = 0);
  /// Composites every screen pixel over what the framebuffer bound at the
  /// call already holds (the host's opaque image), at viewport (0, 0,
  /// screen): the pass outputs premultiplied colour C and alpha 1 - T and
  /// blends it with (GL_ONE, GL_ONE_MINUS_SRC_ALPHA) for colour and alpha, so
  /// the result is C + T * destination, and a pixel with nothing stored keeps
  /// its colour exactly. The host's blend setup is restored afterwards.
  PassTiming resolve_over();

  /// The fragments the last frame captured, in arrival order.
  [[nodiscard]] std::vector<Fragment> read_capture() const;
  /// Every buffer: the technique's and the frame's (tallies, parameters,
  /// capture and deferred-call buffers).
  [[nodiscard]] std::uint64_t memory_bytes() const;
  /// Of those, the capture buffer's (a tool of the CPU path and the reference, not the technique's).
  [[nodiscard]] std::uint64_t capture_bytes() const;

 protected:
  /// Writes the parameter block (the frame's fields and the technique's).
  void write_params() const;
  /// The host sized the container itself (GlHaBuffer::resize): no counting
  /// gather, and no count of a frame before decides the next size.
  void sized_by_host() {
    needs_count_ = false;
    latest_count_.reset();
    sizing_floor_ = frames_;
  }

 private:
  struct Gpu;
  void reset_frame_state() const;
  /// The module without its fingerprint define (module_source adds it).
  [[nodiscard]] std::string module_text(ShaderStage stage, std::string_view header = {}) const;
  /// Throws GlError when calls came from another driver's module
  /// (HABUFFER_COUNTER_FOREIGN) or from a framebuffer of another sample
  /// count than the buffer's (HABUFFER_COUNTER_SAMPLES_MISMATCH).
  void check_refused_calls(const std::vector<std::uint32_t>& words) const;
  /// The counting gather (the host's gather with habuffer_gather_phase
  /// HABUFFER_PHASE_COUNT: every on-screen call counted, nothing inserted)
  /// and size_for its count, timed into report.count.
  void count_and_size(const std::function<void()>& gather, FrameReport& report);
  /// The host's gather in phase `phase` (fill or count), inside a state guard
  /// with the Gather passes around it, then `after` with our buffers bound again.
  void run_phase_gather(std::uint32_t phase, const std::function<void()>& gather, FrameReport& report,
                        const std::function<void()>& after = {});
  void grow_capture(std::uint64_t needed);
  void grow_deferred(std::uint64_t needed);
  /// Reads the tallies into the report (merged duplicates moved, sort
  /// checked); returns the counter words, for the technique's own.
  std::vector<std::uint32_t> read_counters(FrameReport& report) const;
  /// The same from words already read (a deferred frame's readback slot).
  std::vector<std::uint32_t> read_counters_from(std::vector<std::uint32_t> words, FrameReport& report) const;
  /// Whether the technique declared a pass of `stage`.
  [[nodiscard]] bool has_passes(GlPassStage stage) const;
  /// Runs the technique's passes of `stage` in their order (Gather: their `run`).
  void run_passes(GlPassStage stage, FrameReport& report) const;
  /// The Gather passes' `finish`, right after the host's gather.
  void finish_gather_passes() const;
  /// The Fill stage: a gather that inserts nothing, then the Fill passes;
  /// returns its wall time (ms).
  double run_fill(const std::function<void()>& gather, FrameReport& report);
  /// Resume rounds while deferred calls remain (at most resume_rounds): returns
  /// the calls still deferred after the last round; none are run when the
  /// gather deferred more than the buffer holds (deferred_overflow_).
  std::uint64_t resume_deferred(FrameReport& report);
  /// One resume round over the calls deferred in buffer `in` (at most
  /// `count`; the pass reads the buffer's own count too), deferring again
  /// into the other buffer, whose index it returns.
  int dispatch_resume_round(int in, std::uint64_t count);
  PassTiming run_resolve(glm::vec3 background, unsigned background_texture, bool over);
  void run_gather(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls,
                  FrameReport& report);
  /// Readback::Deferred's one gather: resume rounds and the sort recorded
  /// without a read-back, the counters copied into a readback slot behind a fence.
  void run_deferred_gather(const std::function<void()>& gather, FrameReport& report);
  /// The reports of deferred frames whose fences signalled (all with `wait`),
  /// each completed from its slot's words; the latest sizing count taken.
  std::vector<FrameReport> collect_late(bool wait);
  /// Whether lossless mode may regather after `report`'s last attempt
  /// (GlFrameOptions::attempt_budget_ms, growth_budget).
  [[nodiscard]] bool within_budget(const FrameReport& report, std::uint64_t start_capacity,
                                   double elapsed_ms) const;
  /// Records the sizing count of a complete frame (the next frame decides from it).
  void note_count(const FrameReport& report);
  /// Calls the gather entered (the module's own count, where needs_call_count())
  /// less those that ended with an outcome: counted failed_iter and cut short.
  void count_ended_by_driver(std::uint64_t made, FrameReport& report) const;
  /// The same from the module's own count (HABUFFER_COUNTER_CALLS in
  /// `words`), where the gather's shaders were built from module_source().
  void count_own_calls(std::span<const std::uint32_t> words, FrameReport& report) const;
  [[nodiscard]] std::uint64_t read_capture_count() const;
  [[nodiscard]] std::uint64_t read_deferred_count(int which) const;

  std::unique_ptr<GlTechnique> technique_;
  GlFrameOptions options_;
  std::uint32_t made_attempts_ = 1;  // options_.max_attempts as resolved by the constructor
  std::uint64_t capture_capacity_ = 0;
  std::uint64_t deferred_capacity_ = 0;
  std::uint64_t deferred_overflow_ = 0;  ///< calls the last gather deferred, when more than the buffer held
  std::uint64_t frames_ = 0;
  bool sorted_ = false;  ///< the last gather ran the technique's sort pass
  bool needs_call_count_ = false;
  bool needs_count_ = false;
  std::uint32_t module_id_ = 0;  ///< HABUFFER_MODULE_ID of module_source(), in the parameter block  ///< the next frame runs the counting gather (counts_next_frame)
  std::uint32_t gather_phase_ = 0;  ///< the parameter habuffer_gather_phase (HABUFFER_PHASE_*)
  std::optional<SizingCount> latest_count_;  ///< the latest complete frame's count, not yet decided from
  std::uint64_t sizing_floor_ = 0;
  bool stop_at_failure_ = false;
  std::uint32_t late_rounds_ = 0;  ///< Readback::Deferred: resume rounds the next frame dispatches  ///< the parameter habuffer_stop_at_failure of the attempt being gathered
  std::vector<FrameReport> held_reports_;  ///< deferred reports read by resize_screen, for the next frame()  ///< counts of frames before this one are not sized by (a resize_screen since)
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
