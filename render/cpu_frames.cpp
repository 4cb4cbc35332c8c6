// The CPU path of `habuffer render`: the GPU rasterizes and captures every
// fragment (inserting nothing), the technique runs on the CPU over the
// capture, and the image is composited on the CPU over the opaque pass.
#include <chrono>

#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer {
namespace {

class CpuFrames final : public FramePath {
 public:
  CpuFrames(const RenderSettings& s, gl::AtomicMode mode)
      : settings_(s), capture_(capture_config(s), s.offsets, mode, capture_options()), builder_(s) {}

  gl::GlFrameDriver& driver() override { return capture_; }

  void size_for(std::uint64_t fragments, RenderResult&) override { builder_.size_for(fragments); }

  void complete_frame(const gl::FrameReport&, SceneRenderer& renderer, FrameStats& fs, RenderResult& result) override {
    std::vector<Fragment> fragments = capture_.read_capture();
    const TechniqueBuild& last = builder_.build(fragments, fs);
    result.growth_limited = result.growth_limited || last.growth_limited;
    if (last.too_deep) result.too_deep = last.too_deep;
    const auto r0 = std::chrono::steady_clock::now();
    result.backgrounds = renderer.read_opaque_colour();
    result.image = Image{settings_.config.screen, last.buffer->composite_image(result.backgrounds, settings_.threads)};
    fs.resolve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
    result.fragments = std::move(fragments);  // the last frame's stay (reference, culled heat map)
  }

  void finish(SceneRenderer&, RenderResult& result) override {
    finish_cpu_result(settings_, builder_.release(), result);
    result.device = "cpu, fragments rasterized by gl (" + gl::query_gl_info().renderer + ")";
  }

 private:
  const RenderSettings& settings_;
  gl::GlHaBuffer capture_;
  CpuFrameBuilder builder_;
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
std::unique_ptr<FramePath> make_vulkan_frames(const RenderSettings& settings, gl::AtomicMode mode);

std::unique_ptr<FramePath> make_frame_path(const RenderSettings& settings, gl::AtomicMode mode) {
  if (settings.path == RenderPath::Cpu) return std::make_unique<CpuFrames>(settings, mode);
  if (settings.path == RenderPath::Vk) return make_vulkan_frames(settings, mode);
  return make_gpu_frames(settings, mode);
}

}  // namespace habuffer
