/// @file
/// One technique's buffers and passes on the GPU (its "container"), behind
/// the interface the technique-neutral frame driver (GlFrameDriver) runs:
/// the driver owns the frame (state guard, parameters, outcome tallies,
/// capture, deferred calls, retries, lossless regathers, resolve, timers) and
/// asks the technique to empty itself, to sort after the gather, to grow when
/// it dropped fragments, and for its memory.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "habuffer/fragment_buffer.h"
#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_context.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique_params.h"

namespace habuffer::gl {

/// The parameter block every module reads (std140), one struct for both paths (technique_params.h).
using GlParams = ParamBlock;

/// Where in a frame the driver runs a pass a technique declares (GlPass).
/// A frame is: FrameStart passes, the technique's sizing (begin_frame), then
/// per attempt the buffers emptied (before_gather), a Fill gather if any, the
/// host's gather inside the Gather passes, the resume rounds of calls cut
/// short, and the Sort passes.
enum class GlPassStage : std::uint8_t {
  /// Once, before the frame's first gather, inside a state guard with the
  /// parameters written and every buffer bound: the HA-buffer's clear pass,
  /// which counts and empties the last frame's records.
  FrameStart,
  /// A gather of the host's scene that inserts nothing (the parameter
  /// habuffer_gather_phase 1, inside the Gather passes too), then `run` with every
  /// buffer bound: the k-buffer's occupancy fill and its count pass. The
  /// inserting gather follows.
  Fill,
  /// Around every gather of the host's, inside its state guard with every
  /// buffer bound: `run` right before (the framebuffer and blend state the
  /// host's draws need beyond the buffers), `finish` right after (the
  /// blended baselines copy their accumulators out). The guard gives the
  /// host's state back afterwards.
  Gather,
  /// After every gather the frame keeps (not one a full capture or deferred
  /// buffer repeats), every buffer bound: the sort pass of lists and arrays.
  /// It writes its time into the report's `sort` (a technique declares one).
  Sort,
};

/// What a pass is given: the frame's report and options.
struct GlPassContext {
  FrameReport& report;            ///< the frame's report (a pass may add its timing or counts)
  const GlFrameOptions& options;  ///< the frame's options (finish_timing, policy, ...)
};

/// One pass of a technique's frame (see GlPassStage): its stage, a name for
/// timings and errors, and what it runs. Declared by the container in its
/// constructor, with the program it owns.
struct GlPass {
  GlPassStage stage;                           ///< when it runs
  std::string name;                            ///< "the lists' sort pass": the driver's GL error check names it
  std::function<void(GlPassContext&)> run;     ///< the pass (Gather: before the host's gather)
  std::function<void()> finish = {};           ///< Gather only: right after the host's gather
  unsigned framebuffer = 0;                    ///< Gather only: what the host's gather draws into (0: the host's)
};

/// One technique's container on the GPU, run by GlFrameDriver (see the file
/// comment); make_gl_technique makes one.
class GlTechnique {
 public:
  /// Records what every container shares and checks the binding points
  /// against the current context's limits (GlBindings::validate: GlError),
  /// before the container compiles anything with them.
  GlTechnique(Technique technique, AtomicMode mode, const GlBindings& bindings, Extent screen,
              std::uint32_t samples = 1);
  /// Virtual: frame drivers own containers through this base.
  virtual ~GlTechnique();
  GlTechnique(const GlTechnique&) = delete;
  GlTechnique& operator=(const GlTechnique&) = delete;

  /// The technique this container runs.
  [[nodiscard]] Technique technique() const { return technique_; }
  /// Throws GlError naming `call` unless the context the container was
  /// made on is current on this thread (gl_context.h): the frame driver
  /// checks before every call that reaches GL.
  void check_context(const char* call) const { context_.check(call); }
  /// The context the container was made on.
  [[nodiscard]] const ContextBound& context() const { return context_; }
  /// The atomic mode, which fixes the record layout.
  [[nodiscard]] AtomicMode mode() const { return mode_; }
  /// The binding points of its buffers.
  [[nodiscard]] const GlBindings& bindings() const { return bindings_; }
  /// The screen, in pixels.
  [[nodiscard]] Extent screen() const { return screen_; }
  /// The samples per pixel its records carry masks of (BufferConfig::samples; 1: none).
  [[nodiscard]] std::uint32_t samples() const { return samples_; }
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
  /// The passes the technique adds to a frame, each run by the driver at its
  /// stage (GlPass); the same list for the container's life.
  [[nodiscard]] const std::vector<GlPass>& passes() const { return passes_; }
  /// The framebuffer the host's gather must draw into (the Gather pass's,
  /// for the techniques that blend there: wboit, blend; the driver binds it,
  /// so a host that leaves the binding alone needs nothing); 0 for the
  /// others, which draw nothing and leave the framebuffer to the host.
  [[nodiscard]] unsigned gather_framebuffer() const;
  /// At a frame's start, after its FrameStart passes, with no GL state
  /// touched: adapt the size (SPEC 8) from what the last frame asked for.
  virtual void begin_frame(FrameReport& report, const GlFrameOptions& options) = 0;
  /// Right before every gather, the frame's first and its regathers: empty
  /// what the last gather filled (heads, counts, max-age table, ...).
  virtual void before_gather() = 0;
  /// Empties what a gather inserted, for a regather of the same frame.
  virtual void reset() = 0;
  /// After every gather, with the driver's counter words read back (the
  /// layout of entry_common.glsl's HaCounters; the tallies are already in
  /// report.counters): the technique's own fields of the report, and what
  /// it keeps for the next frame's sizing (the lists' nodes requested, the
  /// arrays' deepest pixel, the HA-buffer's table).
  virtual void gathered(std::span<const std::uint32_t> counter_words, FrameReport& report);
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
  /// The HA-buffer's table now (FrameReport::table); zero for other techniques.
  [[nodiscard]] virtual Extent table_extent() const { return {}; }
  /// Whether the container was made without a size for what it stores (the
  /// HA-buffer's table or the lists' pool not given): the frame driver then
  /// counts the first frame's fragments before its gather (and again after
  /// a resize_screen), sizes it by fit_automatic_size, and adapts it every
  /// frame by SPEC 8 (GlFrameDriver::frame).
  [[nodiscard]] virtual bool sized_automatically() const { return false; }
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

  /// What the depths of the last frame's records are (the light whose t
  /// they hold, or window depth by convention and window mapping), recorded
  /// by the frame driver at every frame; nullopt before the first.
  /// GlShadowLookup checks it against its mapping (light_depth_mismatch).
  [[nodiscard]] const std::optional<GlGatherDepth>& gather_depth() const { return gather_depth_; }
  /// The frame driver's record of it, at the start of every frame.
  void record_gather_depth(const GlGatherDepth& depth) { gather_depth_ = depth; }

 protected:
  /// Adds a pass to passes() (a container declares its passes in its constructor).
  void declare_pass(GlPass pass) { passes_.push_back(std::move(pass)); }
  /// resize_screen's work, for a screen that is not empty, fits the
  /// viewport and differs from screen(): check every limit, make the new
  /// buffers, and only then replace the old ones (strong guarantee).
  /// screen() is still the old one during the call.
  virtual void change_screen(Extent screen) = 0;

 private:
  ContextBound context_;  ///< first: checked before the bindings query the context
  Technique technique_;
  AtomicMode mode_;
  GlBindings bindings_;
  Extent screen_;
  std::uint32_t samples_;  ///< BufferConfig::samples
  std::vector<GlPass> passes_;
  std::optional<GlGatherDepth> gather_depth_;
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

/// Throws GlError unless a buffer of `bytes` fits one shader-storage buffer
/// of this context (the message names `what` and the sizes).
void check_storage_fits(std::uint64_t bytes, const std::string& what);
/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
std::uint64_t max_storage_bytes();
/// Throws GlError unless `screen` fits this context's largest viewport
/// (GL_MAX_VIEWPORT_DIMS; the message names both).
void check_viewport_fits(Extent screen);
/// What this context's multisampled images hold.
struct MultisampleLimits {
  /// The smallest of GL_MAX_SAMPLES, GL_MAX_COLOR_TEXTURE_SAMPLES,
  /// GL_MAX_DEPTH_TEXTURE_SAMPLES and GL_MAX_FRAMEBUFFER_SAMPLES, and its name.
  int largest = 0;
  std::string limited_by;
  /// The counts above 1 that the float formats of a host's passes (RGBA32F,
  /// R32F, DEPTH_COMPONENT32F multisampled textures) all hold exactly
  /// (GL_SAMPLES), ascending, none beyond `largest`.
  std::vector<std::uint32_t> counts;
};
MultisampleLimits multisample_limits();
/// Throws GlError unless this context's multisampled images hold exactly
/// `samples` samples a pixel (1 always fits): within MultisampleLimits'
/// largest and among its counts (an implementation may round a count up, so
/// a rasterizer's masks would name samples the buffer has no bits for).
/// One line naming --samples, the count and the limit, before any image is
/// made: habuffer render and habuffer-view call it; a host with images of
/// its own may.
void check_samples_fit(std::uint32_t samples);

}  // namespace habuffer::gl
