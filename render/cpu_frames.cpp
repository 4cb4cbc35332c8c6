// The paths of `habuffer render` that rasterize with GL's capture: the GPU
// rasterizes and captures every fragment (inserting nothing); a
// FrameBuilder builds the technique over the capture and composites it over
// the opaque pass, on the CPU (CpuFrameBuilder) or on a Vulkan device
// (vulkan_frames.cpp).
#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer {
namespace {

class CapturedFrames final : public FramePath {
 public:
  CapturedFrames(const RenderSettings& s, gl::AtomicMode mode, std::unique_ptr<FrameBuilder> builder)
      : settings_(s), capture_(capture_config(s), s.offsets, mode, capture_options()), builder_(std::move(builder)) {}

  gl::GlFrameDriver& driver() override { return capture_; }

  void size_for(std::uint64_t fragments, RenderResult&) override { builder_->size_for(fragments); }

  void complete_frame(const gl::FrameReport&, SceneRenderer& renderer, FrameStats& fs, RenderResult& result) override {
    std::vector<Fragment> fragments = capture_.read_capture();
    result.backgrounds = renderer.read_opaque_colour();
    const TechniqueBuild& last = builder_->build(fragments, result.backgrounds, fs);
    result.growth_limited = result.growth_limited || last.growth_limited;
    if (last.too_deep) result.too_deep = last.too_deep;
    result.image = Image{settings_.config.screen, builder_->image(fs)};
    result.fragments = std::move(fragments);  // the last frame's stay (reference, culled heat map)
  }

  void finish(SceneRenderer&, RenderResult& result) override {
    finish_cpu_result(settings_, builder_->release(), result);
    result.device = builder_->device() + ", fragments rasterized by gl (" + gl::query_gl_info().renderer + ")";
  }

 private:
  const RenderSettings& settings_;
  gl::GlHaBuffer capture_;
  std::unique_ptr<FrameBuilder> builder_;
};

}  // namespace

std::string_view to_string(RenderPath path) {
  switch (path) {
    case RenderPath::Gl: return "gl";
    case RenderPath::Cpu: return "cpu";
    case RenderPath::Vk: return "vk";
  }
  return "gl";
}

std::unique_ptr<FramePath> make_gpu_frames(const RenderSettings& settings, gl::AtomicMode mode);
std::unique_ptr<FrameBuilder> make_vulkan_frame_builder(const RenderSettings& settings);

std::unique_ptr<FramePath> make_frame_path(const RenderSettings& settings, gl::AtomicMode mode) {
  if (settings.path == RenderPath::Cpu)
    return std::make_unique<CapturedFrames>(settings, mode, std::make_unique<CpuFrameBuilder>(settings));
  if (settings.path == RenderPath::Vk)
    return std::make_unique<CapturedFrames>(settings, mode, make_vulkan_frame_builder(settings));
  return make_gpu_frames(settings, mode);
}

}  // namespace habuffer
