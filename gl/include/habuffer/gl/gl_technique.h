/// @file
/// One technique's buffers and passes on the GPU (its "container"), behind
/// the interface the technique-neutral frame driver (GlFrameDriver) runs:
/// the driver owns the frame (state guard, parameters, outcome tallies,
/// capture, deferred calls, retries, lossless regathers, resolve, timers) and
/// asks the technique to empty itself, to sort after the gather, to grow when
/// it dropped fragments, and for its memory.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "habuffer/fragment_buffer.h"
#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique_params.h"

namespace habuffer::gl {

/// The parameter block every module reads (std140), one struct for both paths (technique_params.h).
using GlParams = ParamBlock;

/// One technique's container on the GPU, run by GlFrameDriver (see the file
/// comment); make_gl_technique makes one.
class GlTechnique {
 public:
  /// Records what every container shares and checks the binding points
  /// against the current context's limits (GlBindings::validate: GlError),
  /// before the container compiles anything with them.
  GlTechnique(Technique technique, AtomicMode mode, const GlBindings& bindings, Extent screen);
  /// Virtual: frame drivers own containers through this base.
  virtual ~GlTechnique();
  GlTechnique(const GlTechnique&) = delete;
  GlTechnique& operator=(const GlTechnique&) = delete;

  /// The technique this container runs.
  [[nodiscard]] Technique technique() const { return technique_; }
  /// The atomic mode, which fixes the record layout.
  [[nodiscard]] AtomicMode mode() const { return mode_; }
  /// The binding points of its buffers.
  [[nodiscard]] const GlBindings& bindings() const { return bindings_; }
  /// The screen, in pixels.
  [[nodiscard]] Extent screen() const { return screen_; }
  /// The GLSL module host shaders append their code to (technique_module).
  [[nodiscard]] std::string module_source(ShaderStage stage, std::string_view header = {}) const;

  /// Changes the screen in place (a host's window resize): the next frame
  /// stores every pixel of `screen` and nothing of the last frame. Every
  /// per-pixel buffer is made anew for `screen` (zeroed); what the container
  /// learned is kept where it does not depend on the screen (K of fixed
  /// arrays and the k-buffer) and scaled with it where it does (the
  /// HA-buffer's table by each side's ratio, at least the screen; the node
  /// pool by the area's ratio), see each container. The limits are checked
  /// first, with the one-line errors of construction: std::invalid_argument
  /// for an empty screen or one beyond the configuration's rules, GlError
  /// for one beyond this context's (viewport, buffer sizes). On a throw the
  /// container is unchanged and keeps working at its old screen (strong
  /// guarantee). The same screen is a no-op. Touches no binding of the
  /// host's (buffers and textures are made and cleared by name).
  void resize_screen(Extent screen);

  /// The technique's fields of the parameter block.
  virtual void write_params(GlParams& params) const = 0;
  /// Binds the technique's storage buffers at their points.
  virtual void bind() const = 0;
  /// At a frame's start, inside the driver's state guard with every buffer
  /// bound: count and empty what the previous frame left where the technique
  /// does so (the HA-buffer's clear pass), and adapt the size (SPEC 8).
  virtual void begin_frame(FrameReport& report, const GlFrameOptions& options) = 0;
  /// Whether begin_frame will run a GL pass (the driver then guards the
  /// host's state and binds every buffer first).
  [[nodiscard]] virtual bool draws_at_frame_start() const { return false; }
  /// Right before every gather, the frame's first and its regathers.
  virtual void before_gather() = 0;
  /// Inside the gather's state guard, right before the host's gather (and its
  /// fill pass): the GL state its insert calls need beyond the buffers. The
  /// blended baselines bind their framebuffer and blend setup here; the guard
  /// gives the host's state back afterwards. Nothing by default.
  virtual void enter_gather() const {}
  /// Right after the host's gather, still inside that guard, before any
  /// resume or sort pass (the blended baselines copy their framebuffer into
  /// the storage buffers the resolve reads). Nothing by default.
  virtual void leave_gather() const {}
  /// The framebuffer the host's gather must draw into, for the techniques
  /// that blend there (wboit, blend; enter_gather binds it, so a host that
  /// leaves the binding alone needs nothing); 0 for the others, which draw
  /// nothing and leave the framebuffer to the host.
  [[nodiscard]] virtual unsigned gather_framebuffer() const { return 0; }
  /// Passes of the host's gather per attempt: 2 when the technique first
  /// needs a pass that inserts nothing (the k-buffer's occupancy fill, the
  /// parameter ha_gather_phase 1), then between_passes() with every buffer
  /// bound, then the insertion pass.
  [[nodiscard]] virtual std::uint32_t gather_passes() const { return 1; }
  /// Between the two passes of such a gather (nothing by default).
  virtual void between_passes() {}
  /// Empties what a gather inserted, for a regather of the same frame.
  virtual void reset() = 0;
  /// After every gather, with every buffer bound: the sort pass, if any.
  virtual PassTiming after_gather(bool finish_timing);
  /// Whether after_gather sorts every pixel (its sort pass counts each one).
  [[nodiscard]] virtual bool sorts() const { return false; }
  /// After every gather's counters are read (the report holds them).
  virtual void gathered(const FrameReport& report);
  /// Lossless mode: room for what the last gather dropped (the report's
  /// counters and counts; the driver retries calls cut short itself); false
  /// when this context cannot hold more.
  virtual bool grow(const FrameReport& report, const GlFrameOptions& options) = 0;
  /// Whether a frame that dropped fragments is gathered again into a grown
  /// container even without lossless mode (max_attempts 1): the automatic
  /// pool of linked lists. One such regather, then max_attempts rules.
  [[nodiscard]] virtual bool grows_at_once() const { return false; }
  /// Whether insert calls can be cut short and deferred (the HA-buffer's probe loop).
  [[nodiscard]] virtual bool defers_calls() const { return false; }
  /// Records the technique can hold now.
  [[nodiscard]] virtual std::uint64_t capacity() const = 0;
  /// The HA-buffer's current table (zero for other techniques).
  [[nodiscard]] virtual Extent table() const { return {}; }
  /// Sizes an automatically sized container before its first frame from the
  /// counting pass: `wanted` says the table or pool the fragments need; the
  /// container takes the largest up to it this OpenGL holds. Returns whether
  /// the limits made it smaller. Containers of a fixed size ignore it.
  virtual bool fit_automatic_size(const TechniqueConfig& wanted) {
    (void)wanted;
    return false;
  }
  /// The largest cell of the max-age table, read back (0 for containers
  /// without one).
  [[nodiscard]] virtual std::uint32_t read_largest_max_age() const { return 0; }
  /// Bytes of the technique's own buffers.
  [[nodiscard]] virtual std::uint64_t memory_bytes() const = 0;
  /// The last frame's state as a CPU container of the same technique (lists,
  /// dumps, compositing on the CPU), its insert counters left to the caller.
  [[nodiscard]] virtual std::unique_ptr<FragmentBuffer> read_back() const = 0;

 protected:
  /// resize_screen's work, for a screen that is not empty, fits the
  /// viewport and differs from screen(): check every limit, make the new
  /// buffers, and only then replace the old ones (strong guarantee).
  /// screen() is still the old one during the call.
  virtual void change_screen(Extent screen) = 0;

 private:
  Technique technique_;
  AtomicMode mode_;
  GlBindings bindings_;
  Extent screen_;
};

/// The container of config.technique on the GPU (offsets and the clear
/// pass's tile side are the HA-buffer's; GlFrameOptions::clear_tile).
std::unique_ptr<GlTechnique> make_gl_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                                               AtomicMode mode, const GlBindings& bindings = {},
                                               std::uint32_t clear_tile = 0);

/// Throws GlError unless `mode` holds `layout`'s records (native32: L32;
/// native64, emulated64: L64) and this context has what the mode needs
/// (64-bit shader types; native64 also 64-bit atomics).
void check_atomic_mode(AtomicMode mode, Layout layout);
/// Emulated64's lock words for `slots` slots: one per 2^HABUFFER_LOCK_SHIFT.
std::uint64_t emulated64_lock_words(std::uint64_t slots);

/// Throws GlError unless a buffer of `bytes` fits one shader-storage buffer
/// of this context (the message names `what` and the sizes).
void check_storage_fits(std::uint64_t bytes, const std::string& what);
/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
std::uint64_t max_storage_bytes();
/// Throws GlError unless `screen` fits this context's largest viewport
/// (GL_MAX_VIEWPORT_DIMS; the message names both).
void check_viewport_fits(Extent screen);

}  // namespace habuffer::gl
