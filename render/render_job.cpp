#include "habuffer/render/render_job.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/render/scene_renderer.h"

namespace habuffer {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

void validate(const RenderSettings& s) {
  s.policy.validate();
  if (s.frames == 0) throw std::invalid_argument("--frames must be at least 1");
  if (s.max_attempts == 0) throw std::invalid_argument("--max-attempts must be at least 1");
  technique_config(s).validate();
  check_runs_on_path(s.path, s.technique);
  if (s.shadows) s.shadows->validate();
  if (s.shadows && s.config.layout == Layout::L32)
    throw std::invalid_argument("--shadows needs --layout 64: the view's shaders read the light buffer's 64-bit "
                                "records with 64-bit shader integers, which an L32 view's module does not enable");
}

void finish_stats(FrameStats& fs) {
  fs.load_factor = fs.capacity > 0 ? static_cast<double>(fs.counters.stored()) / static_cast<double>(fs.capacity) : 0.0;
}

}  // namespace

bool automatic_size(const RenderSettings& s) {
  if (uses_table(s.technique)) return s.config.table == Extent{};
  if (uses_pool(s.technique)) return s.pool_capacity == 0;
  return false;
}

std::uint32_t frame_attempts(const RenderSettings& s) { return automatic_size(s) || s.lossless ? s.max_attempts : 1; }

TechniqueConfig technique_config(const RenderSettings& s) {
  TechniqueConfig c;
  static_cast<TechniqueChoice&>(c) = s;
  c.buffer = s.config;
  c.buffer.table = s.config.table_or_screen();
  if (c.pool_capacity == 0) c.pool_capacity = s.config.screen.area();  // auto: a placeholder until the counting pass
  return c;
}

namespace {

// The GPU path sees no records before inserting, only the counting pass: a
// pixel with more fragments than AMAX (without early cull, which could cull
// them) fails an HA-buffer at any table size unless they are duplicates.
bool age_limit_applies(const RenderSettings& s) {
  return s.path == RenderPath::Gl && counted_depth_bounds_growth(s.technique, s.config);
}
std::optional<PixelDepth> pixel_beyond_amax(const RenderSettings& s, std::span<const std::uint32_t> counts) {
  return pixel_counted_beyond(counts, s.config.screen, s.config.record_layout().max_age());
}

}  // namespace

namespace {

// What one render_scene call holds across its frames.
struct SceneRender {
  const Scene& scene;
  const RenderSettings& s;
  FramePath& path;
  SceneRenderer& renderer;
  LightPass* light;  // nullptr without --shadows
  RenderResult& result;

  void bind_light() const {
    if (light) light->bind();
  }

  // Frame 0 only: the counting pass sizes the first table or pool, so frame 0
  // need not fail its way up.
  void size_from_count(const Camera& camera) const {
    gl::GlFrameDriver& driver = path.driver();
    driver.bind();  // the gather shader's uniform block, even though counting inserts nothing
    const std::uint64_t fragments = renderer.count_fragments(camera);
    if (fragments > UINT32_MAX)
      throw gl::GlError("a frame of " + std::to_string(fragments) +
                        " fragments overflows the GPU path's 32-bit counters: render a smaller view or fewer layers");
    path.size_for(fragments, result);
    // Where frames may grow, no frame grows for such a pixel (16 growths to
    // a 4 GB table otherwise); the read-back is only paid there.
    if (age_limit_applies(s) && frame_attempts(s) > 1)
      if ((result.too_deep = pixel_beyond_amax(s, renderer.read_pixel_fragments()))) driver.limit_attempts(1);
  }

  // Frame k at its orbit angle: opaque pass, (frame 0) sizing, the technique's frame.
  Camera frame(std::uint32_t k) const {
    const auto t0 = Clock::now();
    FrameStats fs;
    fs.index = k;
    fs.yaw = s.camera.yaw + (s.orbit ? 360.0f * static_cast<float>(k) / static_cast<float>(s.frames) : 0.0f);
    CameraParams params = s.camera;
    params.yaw = fs.yaw;
    const Camera camera = frame_scene(scene, params, s.config.screen);
    bind_light();
    renderer.draw_opaque(camera, s.background);
    if (k == 0) size_from_count(camera);
    const gl::FrameReport report = path.driver().frame(
        [&] {
          bind_light();
          renderer.gather(camera);
        },
        [&] { return renderer.inserted(); });
    fs.opaque_rejected = renderer.read_rejected();
    path.complete_frame(report, renderer, fs, result);
    finish_stats(fs);
    fs.frame_ms = ms_since(t0);
    result.frames.push_back(fs);
    return camera;
  }

  // After the frames: the shadow map seen from the last camera, and what
  // --shadows asked to read back.
  void finish_light(const Camera& camera) const {
    LightStats stats = light->stats();
    bind_light();
    stats.lookup_ms = renderer.shadow_map_pass(camera);
    result.shadow_map = renderer.read_shadow_map();
    stats.lookup_pixels = static_cast<std::uint64_t>(
        std::count_if(result.shadow_map.begin(), result.shadow_map.end(), [](float t) { return t >= 0.0f; }));
    result.light = stats;
    if (s.shadows->read_back) {
      result.light_buffer = light->read_back();
      result.opaque_depth = renderer.read_opaque_depth();
    }
    if (s.shadows->capture) result.light_fragments = light->read_capture();
  }
};

}  // namespace

RenderResult render_scene(const Scene& scene, const RenderSettings& s) {
  validate(s);
  const gl::GlInfo info = gl::query_gl_info();
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(info, s.config.layout);
  if (!mode) throw gl::GlError("--layout 64 needs 64-bit shader types (GL_ARB_gpu_shader_int64), which this OpenGL lacks");
  const std::unique_ptr<FramePath> path = make_frame_path(s, *mode);
  gl::GlFrameDriver& driver = path->driver();
  // The light does not move while the camera orbits: its buffer is built once.
  std::unique_ptr<LightPass> light;
  if (s.shadows) {
    light = std::make_unique<LightPass>(scene, *s.shadows, driver.bindings());
    light->build();
  }
  // The gather counts only what this render reads: fragments per pixel where
  // the driver needs the call count, culled ones for a culled heat map.
  SceneRenderer renderer(scene, s.config.screen, driver,
                         SceneRenderer::GatherCounts{driver.needs_call_count(),
                                                     s.per_pixel_culled && s.config.early_cull_tau > 0.0f},
                         light ? std::optional(light->receiving()) : std::nullopt);
  RenderResult result;
  const SceneRender run{scene, s, *path, renderer, light.get(), result};
  Camera last_camera;
  for (std::uint32_t k = 0; k < s.frames; ++k) {
    last_camera = run.frame(k);
    if (s.on_progress) s.on_progress(k + 1, s.frames);
  }
  result.pixel_fragments = renderer.read_pixel_fragments();
  // Frames that could not grow: the same pixel named for the loss warning.
  const bool failed_age = std::any_of(result.frames.begin(), result.frames.end(),
                                      [](const FrameStats& f) { return f.counters.failed_age > 0; });
  if (!result.too_deep && failed_age && age_limit_applies(s)) result.too_deep = pixel_beyond_amax(s, result.pixel_fragments);
  path->finish(renderer, result);
  if (light) run.finish_light(last_camera);
  result.camera = last_camera;  // validate() asks for at least one frame
  gl::check_gl_errors("rendering");
  return result;
}

RenderResult render_fragments(std::span<const Fragment> fragments, const RenderSettings& s) {
  validate(s);
  if (s.shadows) throw std::invalid_argument("--shadows needs a scene: a recorded stream has no world positions to light");
  RenderResult result;
  CpuFrameBuilder builder(s);
  builder.size_for(fragments.size());
  result.backgrounds.assign(s.config.screen.area(), s.background);
  // Every frame the same stream (a stream has one view), on the kept container.
  for (std::uint32_t k = 0; k < s.frames; ++k) {
    FrameStats fs;
    fs.index = k;
    const auto t0 = Clock::now();
    const TechniqueBuild& b = builder.build(fragments, result.backgrounds, fs);
    result.growth_limited = result.growth_limited || b.growth_limited;
    if (b.too_deep) result.too_deep = b.too_deep;
    result.image = Image{s.config.screen, builder.image(fs)};
    finish_stats(fs);
    fs.frame_ms = ms_since(t0);
    result.frames.push_back(fs);
    if (s.on_progress) s.on_progress(k + 1, s.frames);
  }
  result.pixel_fragments.assign(s.config.screen.area(), 0);
  for (const Fragment& f : fragments) ++result.pixel_fragments[f.x + std::size_t{f.y} * s.config.screen.x];
  result.fragments.assign(fragments.begin(), fragments.end());
  finish_cpu_result(s, builder.release(), result);
  result.device = "cpu";
  return result;
}

}  // namespace habuffer
