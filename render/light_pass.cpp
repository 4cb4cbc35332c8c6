#include "habuffer/render/light_pass.h"

#include <epoxy/gl.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "habuffer/fragment_streams.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/render/scene_renderer.h"

namespace habuffer {
namespace {

// Every mesh through the light buffer: opaque ones inserted at opacity 1
// (see the file comment of light_pass.h), none drawn by the opaque pass.
Scene light_scene(const Scene& scene) {
  Scene s = scene;
  for (Mesh& m : s.meshes) m.insert_opaque = true;
  return s;
}

BufferConfig light_config(const ShadowSettings& s) {
  BufferConfig c;
  c.screen = s.light.size;
  c.layout = Layout::L64;
  c.age_bits = s.age_bits;
  c.table = s.table == Extent{} ? s.light.size : s.table;
  c.early_cull_tau = s.early_cull_tau;
  return c;
}

gl::AtomicMode light_mode() {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode)
    throw gl::GlError("--shadows: the light buffer's L64 records need 64-bit shader types "
                      "(GL_ARB_gpu_shader_int64), which this OpenGL lacks");
  return *mode;
}

gl::GlLightMapping mapping_of(const LightView& v) {
  return {v.camera.view, v.camera.projection, v.camera.near_plane, v.camera.far_plane};
}

// The light buffer's driver is told its light: the gather inserts t itself
// (shading.glsl's r_depth, the lookup's formula), and the lookup checks the
// records are the light's (GlShadowLookup::check_depths).
gl::GlFrameOptions light_options(const ShadowSettings& s, const LightView& light) {
  gl::GlFrameOptions o;
  o.max_attempts = s.table == Extent{} ? 16 : 1;  // automatic: grown until nothing is dropped
  o.capture = s.capture;
  o.light = mapping_of(light);
  return o;
}

}  // namespace

void ShadowSettings::validate() const {
  if (light.size.area() == 0) throw std::invalid_argument("--light-size " + light.size.str() + " has no pixels");
  if (!(std::isfinite(max_slope) && max_slope >= 0.0f))
    throw std::invalid_argument("--shadow-slope must be a finite slope at least 0");
  // The bias rule's bound (shadow_slope_limit): from the map's short side in
  // pixels on, the bias exceeds the whole scene's depth and nothing shadows.
  const bool pcf = filter == ShadowFilter::Pcf;  // doubles the bias
  const double limit = shadow_slope_limit(light.size) / (pcf ? 2.0 : 1.0);
  if (double{max_slope} >= limit) {
    char head[160];
    std::snprintf(head, sizeof head, "--shadow-slope %g must be below %g", static_cast<double>(max_slope), limit);
    throw std::invalid_argument(std::string(head) + " (the short side of --light-size " + light.size.str() +
                                (pcf ? " in pixels, halved by --shadow-filter pcf, which doubles the bias)"
                                     : " in pixels)") +
                                ": a larger bias exceeds the whole scene's depth seen from the light, so nothing "
                                "would cast a shadow");
  }
  if (!(early_cull_tau >= 0.0f && early_cull_tau <= 1.0f))
    throw std::invalid_argument("--light-cull must be in [0, 1] (0: off)");
  try {
    light_config(*this).validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("the light buffer (--light-size, --light-table): ") + e.what());
  }
}

struct LightPass::Gpu {
  Gpu(const Scene& original, const ShadowSettings& s, const gl::GlBindings& view_bindings, const LightView& light,
      std::uint32_t bias)
      : scene(light_scene(original)),
        buffer(light_config(s), OffsetSource{}, light_mode(), light_options(s, light)),
        renderer(this->scene, s.light.size, buffer, SceneRenderer::GatherCounts{buffer.needs_call_count(), false}),
        lookup(buffer.container(), mapping_of(light), bias, view_bindings) {}
  Scene scene;
  gl::GlHaBuffer buffer;
  SceneRenderer renderer;
  gl::GlShadowLookup lookup;
};

LightPass::LightPass(const Scene& scene, const ShadowSettings& settings, const gl::GlBindings& view)
    : settings_(settings) {
  settings_.validate();
  stats_.view = frame_light(scene, settings_.light);
  stats_.size = settings_.light.size;
  const float slope = settings_.filter == ShadowFilter::Pcf ? 2.0f * settings_.max_slope : settings_.max_slope;
  stats_.bias_codes = shadow_bias_codes(stats_.view, slope, light_config(settings_).record_layout().depth_bits());
  try {
    gpu_ = std::make_unique<Gpu>(scene, settings_, view, stats_.view, stats_.bias_codes);
  } catch (const gl::GlError& e) {
    throw gl::GlError(std::string("the light buffer (--light-size ") + settings_.light.size.str() + "): " + e.what());
  }
}

LightPass::~LightPass() = default;

bool LightPass::build() {
  try {
    return gather();
  } catch (const gl::GlError& e) {
    throw gl::GlError(std::string("the light buffer (--light-size ") + settings_.light.size.str() + "): " + e.what());
  }
}

bool LightPass::gather() {
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  const Camera& camera = stats_.view.camera;
  Gpu& g = *gpu_;
  g.renderer.draw_opaque(camera, glm::vec3(1.0f));  // nothing is opaque here: the depth image says "none"
  if (settings_.table == Extent{}) {
    g.buffer.bind();
    const std::uint64_t fragments = g.renderer.count_fragments(camera);
    // A pixel deeper than AMAX fails at any table: no growth for it (render_job's rule for the view).
    if (settings_.early_cull_tau <= 0.0f)
      if ((stats_.too_deep = pixel_counted_beyond(g.renderer.read_pixel_fragments(), settings_.light.size,
                                                  light_config(settings_).record_layout().max_age())))
        g.buffer.limit_attempts(1);
    g.buffer.resize(ResizePolicy{}.initial_table(settings_.light.size, fragments));  // SPEC 8's first table
  }
  const gl::FrameReport report =
      g.buffer.frame([&] { g.renderer.gather(camera); }, [&] { return g.renderer.inserted(); });
  glFinish();
  stats_.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++stats_.builds;
  stats_.attempts = static_cast<std::uint32_t>(report.attempts.size());
  stats_.counters = report.counters;
  stats_.table = g.buffer.table();
  stats_.load_factor = static_cast<double>(report.counters.stored()) / static_cast<double>(stats_.table.area());
  stats_.memory_bytes = g.buffer.technique().memory_bytes() + g.lookup.memory_bytes();  // the capture is a tool's
  stats_.max_age = g.buffer.technique().read_largest_max_age();
  return report.counters.failures() == 0;
}

void LightPass::bind() { gpu_->lookup.bind(); }

ShadowReceiving LightPass::receiving() const {
  return {gpu_->lookup.bindings(), settings_.filter == ShadowFilter::Pcf};
}

std::string to_string(ShadowFilter f) { return f == ShadowFilter::Pcf ? "pcf" : "nearest"; }

std::vector<Fragment> LightPass::read_capture() const {
  return settings_.capture ? gpu_->buffer.read_capture() : std::vector<Fragment>{};
}

std::unique_ptr<FragmentBuffer> LightPass::read_back() const { return gpu_->buffer.technique().read_back(); }

}  // namespace habuffer
