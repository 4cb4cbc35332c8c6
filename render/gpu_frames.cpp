// The GPU path of `habuffer render`: the technique's buffers on the GPU,
// sized automatically from the counting pass, resolved on the GPU into an
// RGBA32F target; the last frame's lists read back for stats and heat maps.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/memory_model.h"
#include "habuffer/render/resolve_target.h"

namespace habuffer {
namespace {

// The technique as the frame driver sizes it: an automatic table or pool
// left unset, so the driver adapts it (render counts frame 0 itself, with
// the per-pixel counts its AMAX check reads, and hands the count to size_for).
TechniqueConfig gpu_technique_config(const RenderSettings& s) {
  TechniqueConfig c = technique_config(s);
  if (automatic_size(s)) {
    if (uses_table(c.technique)) c.buffer.table = Extent{};
    if (uses_pool(c.technique)) c.pool_capacity = 0;
  }
  return c;
}

gl::GlFrameOptions gpu_frame_options(const RenderSettings& s) {
  gl::GlFrameOptions o;
  o.policy = s.policy;
  o.max_attempts = frame_attempts(s);
  o.capture = s.keep_fragments;
  o.module.count_writes = s.count_slot_writes;
  return o;
}

class GpuFrames final : public FramePath {
 public:
  GpuFrames(const RenderSettings& s, gl::AtomicMode mode)
      : settings_(s), mode_(mode), driver_(gl::make_gl_technique(gpu_technique_config(s), s.offsets, mode), gpu_frame_options(s)), target_(s.config.screen) {}

  gl::GlFrameDriver& driver() override { return driver_; }

  void size_for(std::uint64_t fragments, RenderResult& result) override {
    if (!automatic_size(settings_)) return;
    result.growth_limited = driver_.size_for(fragments) || result.growth_limited;
  }

  void complete_frame(const gl::FrameReport& report, SceneRenderer& renderer, FrameStats& fs,
                      RenderResult& result) override {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_.framebuffer());
    fs.sort_ms = report.sort.wall_ms;
    fs.resolve_ms = fs.sort_ms + driver_.resolve(settings_.background, renderer.opaque_colour_texture()).wall_ms;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    fs.table = report.table;
    fs.capacity = report.capacity;
    fs.resized = report.resized;
    fs.attempts = static_cast<std::uint32_t>(report.attempts.size());
    fs.counters = report.counters;
    fs.slot_writes = report.slot_writes;
    fs.deferred = report.deferred;
    fs.resume_rounds = report.resume_rounds;
    fs.resize_limited = report.resize_limited;
    fs.gather_ms = report.gather.wall_ms;
    fs.clear_ms = report.clear.wall_ms + report.reset.wall_ms;
    fs.max_age = driver_.technique().read_largest_max_age();
    result.growth_limited = result.growth_limited || report.growth_limited;
  }

  void finish(SceneRenderer& renderer, RenderResult& result) override {
    result.backgrounds = renderer.read_opaque_colour();
    result.image = target_.read();
    if (settings_.per_pixel_culled) {
      result.pixel_culled = renderer.read_pixel_culled();
      // Without early cull the gather counts none: nothing was culled.
      if (result.pixel_culled.empty()) result.pixel_culled.assign(settings_.config.screen.area(), 0);
    }
    if (settings_.keep_fragments) result.fragments = driver_.read_capture();
    result.buffer = driver_.technique().read_back();
    result.memory_bytes = driver_.memory_bytes() - driver_.capture_bytes();  // the capture serves --reference only
    result.memory_model_bytes = memory_model_bytes(*result.buffer);  // the read-back holds the GPU's sizes
    result.device = "gl " + gl::to_string(mode_) + " on " + gl::query_gl_info().renderer;
  }

 private:
  const RenderSettings& settings_;
  gl::AtomicMode mode_;
  gl::GlFrameDriver driver_;
  ResolveTarget target_;
};

}  // namespace

std::unique_ptr<FramePath> make_gpu_frames(const RenderSettings& settings, gl::AtomicMode mode) {
  return std::make_unique<GpuFrames>(settings, mode);
}

}  // namespace habuffer
