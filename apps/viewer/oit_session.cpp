#include "oit_session.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "habuffer/fragment_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/techniques/ha/ha_buffer.h"

namespace habuffer::view {
namespace {

bool same_view(const Camera& a, const Camera& b) {
  return a.view == b.view && a.projection == b.projection && a.near_plane == b.near_plane &&
         a.far_plane == b.far_plane;
}

}  // namespace

OitSession::OitSession(const GpuMeshes& meshes, TechniqueConfig config, OffsetSource offsets, SessionOptions options)
    : meshes_(meshes), config_(std::move(config)), offsets_(std::move(offsets)), options_(options) {
  driver_ = make_driver(config_, false);
  passes_ = make_passes(*driver_, config_);
}

OitSession::~OitSession() = default;

std::unique_ptr<gl::GlFrameDriver> OitSession::make_driver(const TechniqueConfig& config, bool capture) const {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), config.buffer.layout);
  if (!mode)
    throw gl::GlError("this OpenGL has no atomic mode for --layout " + to_string(config.buffer.layout) +
                      " (64-bit records need GL_ARB_gpu_shader_int64)");
  gl::GlFrameOptions o;
  o.policy = options_.policy;
  if (options_.lossless) o.max_attempts = options_.max_attempts;
  o.capture = capture;
  return std::make_unique<gl::GlFrameDriver>(gl::make_gl_technique(config, offsets_, *mode), o);
}

std::unique_ptr<ViewPasses> OitSession::make_passes(const gl::GlFrameDriver& driver, const TechniqueConfig& config) const {
  if (light_ != nullptr && config.buffer.samples > 1)
    throw std::invalid_argument("translucent shadows are drawn with one sample a pixel: set --samples 1 first");
  return std::make_unique<ViewPasses>(meshes_, driver, light_ != nullptr ? &light_->bindings() : nullptr,
                                      count_pixels_ || guards_depth(driver, config));
}

bool OitSession::guards_depth(const gl::GlFrameDriver& driver, const TechniqueConfig& config) {
  return counted_depth_bounds_growth(config.technique, config.buffer) && driver.made_attempts() > 1;
}

void OitSession::count_pixels(bool on) {
  if (on == count_pixels_) return;
  count_pixels_ = on;
  try {
    std::unique_ptr<ViewPasses> passes = make_passes(*driver_, config_);
    passes_ = std::move(passes);
  } catch (...) {
    count_pixels_ = !on;  // the running passes stay
    throw;
  }
}

std::string OitSession::set_shadows(ShadowLight* light) {
  ShadowLight* before = light_;
  light_ = light;
  try {
    std::unique_ptr<ViewPasses> passes = make_passes(*driver_, config_);
    passes_ = std::move(passes);
    return {};
  } catch (const std::invalid_argument& e) {
    light_ = before;
    return e.what();
  } catch (const gl::GlError& e) {
    light_ = before;
    return e.what();
  }
}

std::string OitSession::reconfigure(TechniqueConfig config) {
  try {
    std::unique_ptr<gl::GlFrameDriver> driver = make_driver(config, false);
    auto passes = make_passes(*driver, config);
    passes_ = std::move(passes);  // the old passes go before the old driver they compiled from
    driver_ = std::move(driver);
    config_ = std::move(config);
    deep_view_.reset();
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const gl::GlError& e) {
    return e.what();
  }
}

void OitSession::resize(Extent screen) {
  const Extent before = driver_->screen();
  if (screen == before) return;
  driver_->resize_screen(screen);  // strong guarantee: on a throw it keeps its old screen
  try {
    std::unique_ptr<ViewPasses> passes = make_passes(*driver_, config_);
    passes_ = std::move(passes);
    config_.buffer.screen = screen;
    driver_->restore_attempts();
    deep_view_.reset();
  } catch (...) {
    driver_->resize_screen(before);  // back to the screen the running passes have
    throw;
  }
}

FrameFigures OitSession::run_frame(gl::GlFrameDriver& driver, ViewPasses& passes, const Camera& camera,
                                   glm::vec3 background) {
  const auto start = std::chrono::steady_clock::now();
  if (light_ != nullptr) light_->bind();  // the lookup's buffers and block, at points of their own
  passes.draw_opaque(camera, background);
  // A regather would grow the table: not for a pixel deeper than AMAX,
  // which no table holds (the failed gather's counts are still in the passes).
  // Once found, the same view of the running driver gathers once (render's
  // limit_attempts(1)); a new view may grow again, and its counts say whether.
  std::optional<PixelDepth> too_deep;
  gl::GrowthCheck may_grow;
  const bool guarded = passes.counts_pixels() && guards_depth(driver, config_);
  const bool running = &driver == driver_.get();
  if (guarded) {
    if (running && deep_view_ && !same_view(*deep_view_, camera)) {
      driver.restore_attempts();
      deep_view_.reset();
    }
    may_grow = [&](const gl::FrameReport&) {
      too_deep = pixel_counted_beyond(passes.read_pixel_fragments(), passes.screen(),
                                      config_.buffer.record_layout().max_age());
      return !too_deep;
    };
  }
  const gl::FrameReport r = driver.frame([&] { passes.gather(camera); }, [&] { return passes.calls(); }, may_grow);
  if (running && guarded) {
    if (deep_view_ && r.counters.failed_age > 0) too_deep = deep_pixel_;  // the view's pixel, counted when found
    if (too_deep && !deep_view_) {
      driver.limit_attempts(1);
      deep_view_ = camera;
      deep_pixel_ = too_deep;
    }
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, passes.image_framebuffer());
  const gl::PassTiming resolve = driver.resolve(background, passes.opaque_colour());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  FrameFigures f;
  f.index = r.index;
  f.counters = r.counters;
  f.capacity = r.capacity;
  f.table = r.table;
  f.attempts = static_cast<std::uint32_t>(r.attempts.size());
  f.too_deep = too_deep;
  f.growth_limited = r.growth_limited;
  f.max_age = driver.technique().read_largest_max_age();
  f.memory_bytes = driver.memory_bytes() - driver.capture_bytes();
  f.clear_ms = r.clear.gpu_ms + r.reset.gpu_ms;
  f.count_ms = r.count.gpu_ms;
  f.gather_ms = r.gather.gpu_ms;
  f.sort_ms = r.sort.gpu_ms;
  f.resolve_ms = resolve.gpu_ms;
  f.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return f;
}

FrameFigures OitSession::frame(const Camera& camera, glm::vec3 background) {
  return run_frame(*driver_, *passes_, camera, background);
}

double OitSession::reference_psnr(const Camera& camera, glm::vec3 background) {
  const Image shown = passes_->read_image();
  // The same view through a capturing driver: its fragments are the frame's.
  std::unique_ptr<gl::GlFrameDriver> capturing = make_driver(config_, true);
  const std::unique_ptr<ViewPasses> passes_ptr = make_passes(*capturing, config_);
  ViewPasses& passes = *passes_ptr;
  run_frame(*capturing, passes, camera, background);
  const std::vector<Fragment> fragments = capturing->read_capture();
  const Image reference = reference_image(fragments, passes.screen(), passes.read_opaque_colour(), config_.buffer.samples);
  return compare_pixels(shown, reference).psnr;
}

std::vector<std::uint32_t> OitSession::max_age_per_pixel() const {
  const std::unique_ptr<FragmentBuffer> back = driver_->technique().read_back();
  const HaBuffer* ha = back ? as_hash_table(*back) : nullptr;
  return ha != nullptr ? habuffer::max_age_per_pixel(*ha) : std::vector<std::uint32_t>{};
}

}  // namespace habuffer::view
