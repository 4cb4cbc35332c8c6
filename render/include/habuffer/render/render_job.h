/// @file
/// `habuffer render` as a library call: frames of a scene through any
/// technique (the HA-buffer, linked lists, fixed arrays, ...) on the GPU path, or
/// rasterized by GL (capture mode) and inserted, sorted and composited on the
/// CPU path, or a recorded fragment stream on the CPU path alone; with
/// everything the stats, heat maps and reference need. The command, the
/// harness and the tests share it so they measure the same frames.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/buffer_config.h"
#include "habuffer/camera.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/technique.h"
#include "habuffer/lossless_build.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/render/image.h"
#include "habuffer/render/light_pass.h"
#include "habuffer/resize_policy.h"
#include "habuffer/scene.h"

namespace habuffer {

/// Where the technique runs.
enum class RenderPath {
  Gl,   ///< on the GPU: the technique's buffers filled and resolved by GL
  Cpu,  ///< GL rasterizes and captures the fragments; the technique runs on the CPU
  Vk    ///< GL rasterizes and captures; the technique is built and resolved on a Vulkan device
};

/// "gl", "cpu" or "vk".
std::string_view to_string(RenderPath path);
/// Whether `path` runs `technique` in this build: every technique on gl and
/// cpu; on vk those with a Vulkan part (false for all where the build has
/// no Vulkan path).
bool runs_on_path(RenderPath path, Technique technique);
/// Throws std::invalid_argument unless runs_on_path, naming the techniques
/// the path runs ("the Vulkan path does not run arrays yet (it runs ...)").
void check_runs_on_path(RenderPath path, Technique technique);

/// Everything one render_scene or render_fragments call runs with
/// (validated there: std::invalid_argument). The technique and its own
/// parameters are the TechniqueChoice base (technique.h): a pool_capacity
/// of 0 means auto: sized from a counting pass (to grow_at use), grown at
/// once when a frame drops, adapted between frames.
struct RenderSettings : TechniqueChoice {
  RenderPath path = RenderPath::Gl;     ///< GPU or CPU path
  /// Screen, layout and age bits (every technique); block, iteration limit,
  /// early cull and table (the HA-buffer). config.table zero means auto: size
  /// the first table from a counting pass, grow at once when a frame fails,
  /// and adapt between frames (SPEC 8). A given table is kept unless lossless.
  BufferConfig config;
  bool lossless = false;  ///< regather with a grown container until nothing is dropped (at most max_attempts)
  std::uint32_t max_attempts = 16;  ///< gathers per frame, lossless and auto (at least 1)
  ResizePolicy policy;    ///< how automatic and lossless sizes grow and adapt
  OffsetSource offsets;   ///< the HA-buffer's probe offsets
  std::uint32_t frames = 1;  ///< at least 1; the camera orbits 360 degrees over the frames (unless !orbit)
  /// false: every frame shows the same view (steady-state timing: frame 0
  /// pays the cold start, later frames reuse what it made).
  bool orbit = true;
  CameraParams camera;         ///< the first frame's view (yaw advanced per frame when orbiting)
  glm::vec3 background{1.0f};  ///< linear RGB behind everything (where no opaque mesh covers)
  bool keep_fragments = false;  ///< capture the last frame's fragments (reference, CPU-side heat maps)
  bool per_pixel_culled = false;  ///< count culled fragments per pixel (CPU path: serial insertion)
  /// GPU path (HA-buffer, k-buffer): tally slot writes (FrameStats::slot_writes),
  /// one more atomic per insert call, compiled into the module only when asked.
  bool count_slot_writes = false;
  std::uint32_t threads = 0;      ///< CPU path: worker threads; 0: the default count (resolve_threads)
  InsertOrder insert_order = InsertOrder::Auto;  ///< CPU path, the HA-buffer (InsertOrder)
  /// Translucent shadows (render_scene only): the light buffer built once
  /// before the first frame (the camera orbits, the light stays), every
  /// opaque and inserted fragment's lit colour times the light's T.
  std::optional<ShadowSettings> shadows;
  /// Called after each frame with (frames done, frames).
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;
};

/// One frame's measurements, in RenderResult::frames.
struct FrameStats {
  std::uint32_t index = 0;       ///< the frame, from 0
  float yaw = 0.0f;              ///< the camera's yaw, degrees
  Extent table;                  ///< HA-buffer: the table the frame ended with
  std::uint64_t capacity = 0;    ///< records the technique could hold (slots, nodes, layers of every pixel)
  bool resized = false;          ///< adaptive sizing changed the table or pool before the frame's first gather
  std::uint32_t attempts = 1;    ///< gathers the frame took (more than 1: lossless or automatic regathers)
  Counters counters;             ///< the frame's insert outcomes (stored, dropped, culled, ...)
  std::uint64_t opaque_rejected = 0;  ///< fragments behind the opaque surfaces, never inserted
  /// GPU path with count_slot_writes: slot raises, evicted records included
  /// (insertion work); nullopt when not counted.
  std::optional<std::uint64_t> slot_writes;
  std::uint64_t deferred = 0;     ///< GPU path: insert calls cut short and resumed (FrameReport::deferred)
  std::uint32_t resume_rounds = 0;  ///< GPU path: passes that resumed deferred calls (FrameReport::resume_rounds)
  bool resize_limited = false;    ///< GPU path: adaptive sizing wanted a table the context cannot hold
  std::uint32_t max_age = 0;     ///< HA-buffer: the largest entry of the max-age table (SPEC 5)
  /// The order the frame was inserted in: the CPU path's HA-buffer says what
  /// Auto chose; every other technique and the GPU path insert in arrival
  /// (rasterization) order.
  InsertOrder insert_order = InsertOrder::Arrival;
  double load_factor = 0.0;      ///< stored / capacity (0 for no capacity)
  /// Milliseconds. gather: the gather pass (resume rounds included); resolve: the sort pass
  /// (lists, arrays) and the compositing; clear (GPU path): the clear pass and
  /// the buffer resets before the gather, which the gather's clock leaves out;
  /// frame: the whole frame, wall clock.
  double gather_ms = 0.0, resolve_ms = 0.0, clear_ms = 0.0, frame_ms = 0.0;
  /// Milliseconds of the sort pass that resolve_ms holds (GPU path: lists,
  /// arrays); 0 where the lists are sorted by the gather (the HA-buffer, the
  /// insertion-sorted techniques, and every CPU container, whose gather sorts).
  /// gather_ms + sort_ms: the cost to sorted lists.
  double sort_ms = 0.0;
};

/// What render_scene and render_fragments return: the last frame's image and lists, every frame's stats.
struct RenderResult {
  Image image;                      ///< the last frame, composited over the background
  std::vector<FrameStats> frames;   ///< one per frame, in order
  std::vector<std::uint32_t> pixel_fragments;  ///< last frame, per pixel (row 0 at the bottom)
  std::vector<std::uint32_t> pixel_culled;     ///< last frame, per pixel (empty unless counted)
  std::vector<glm::vec3> backgrounds;          ///< per pixel: the opaque pass's colour
  std::vector<Fragment> fragments;             ///< last frame (when keep_fragments or path cpu)
  std::unique_ptr<FragmentBuffer> buffer;      ///< the last frame's lists (on the CPU, read back from the GPU)
  /// Every buffer the technique and its frames allocated (GPU: its own, the
  /// tallies, parameters and deferred calls; not the capture, which serves
  /// the CPU path and --reference), in bytes.
  std::uint64_t memory_bytes = 0;
  std::uint64_t memory_model_bytes = 0;        ///< the technique's storage by formula (memory_model.h), bytes
  /// The HA-buffer's last table, or nullptr for other techniques.
  [[nodiscard]] const HaBuffer* ha_buffer() const { return buffer ? as_hash_table(*buffer) : nullptr; }
  /// Where it ran: "gl native32 on llvmpipe ...", "cpu, fragments rasterized by gl (...)", "cpu" (a stream).
  std::string device;
  bool growth_limited = false;  ///< the context could not hold the table the first frame or lossless mode wanted
  /// HA-buffer without early cull: a pixel with more records than AMAX, which
  /// no table holds, so no frame grew for it. The CPU path counts distinct
  /// records; the GPU path, which sees only the counting pass, counts
  /// fragments (duplicates included).
  std::optional<PixelDepth> too_deep;
  /// With shadows: the light buffer's stats, and the light's T at each
  /// pixel's nearest surface in the last frame's view (row 0 at the bottom;
  /// -1 where no surface covers the pixel).
  std::optional<LightStats> light;
  std::vector<float> shadow_map;
  /// With ShadowSettings::read_back: the light buffer on the CPU, and the
  /// last frame's opaque t per pixel (2 where no opaque surface).
  std::unique_ptr<FragmentBuffer> light_buffer;
  std::vector<float> opaque_depth;
  std::vector<Fragment> light_fragments;  ///< with ShadowSettings::capture: the light pass's fragments
  Camera camera;  ///< the last frame's camera (render_scene)
};

/// Renders settings.frames frames of `scene` on settings.path. Needs a current OpenGL 4.5 core context.
/// Throws SceneError, GlError, std::invalid_argument with the reason.
RenderResult render_scene(const Scene& scene, const RenderSettings& settings);

/// Whether the technique's size is automatic in these settings (the
/// HA-buffer's table or the lists' pool; fixed arrays and the k-buffer keep K).
bool automatic_size(const RenderSettings& settings);
/// The attempts a frame may take: max_attempts when lossless or sizes are automatic (they regather), else 1.
std::uint32_t frame_attempts(const RenderSettings& settings);

/// The technique's configuration for the settings (an automatic table or
/// pool given its placeholder: the screen). Not validated.
TechniqueConfig technique_config(const RenderSettings& settings);

/// A recorded stream on the CPU path over the uniform background: every one of settings.frames inserts
/// the same stream (a stream has one view) into the kept container. Needs no GL context; throws
/// std::invalid_argument for invalid settings.
RenderResult render_fragments(std::span<const Fragment> fragments, const RenderSettings& settings);

}  // namespace habuffer
