// The Vulkan path of `habuffer render`: OpenGL rasterizes and captures
// every fragment (inserting nothing), as for the CPU path; the technique is
// built from the capture on a Vulkan device (lossless and automatic
// regathers there, by every path's rule) and resolved there over the opaque
// pass, so the image is the device's. The lists are read back for stats,
// dumps and heat maps.
#include <chrono>
#include <memory>

#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/vk/vulkan_build.h"
#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_registry.h"

namespace habuffer {
namespace {

// Each frame built and resolved on the device; the backgrounds are the
// frame's opaque pass, set before each build.
class VulkanFrameBuilder final : public FrameBuilder {
 public:
  explicit VulkanFrameBuilder(const RenderSettings& settings) : FrameBuilder(settings), builder_(context_) {}

  const vk::VulkanContext& context() const { return context_; }
  void set_backgrounds(std::vector<glm::vec3> backgrounds) { backgrounds_ = std::move(backgrounds); }
  const vk::VulkanResolve& resolved() const { return resolve_; }
  const vk::VulkanBuildInfo& info() const { return info_; }
  TechniqueBuild release() override { return std::move(last_); }

 private:
  const TechniqueBuild& build_frame(const TechniqueConfig& config, std::span<const Fragment> fragments) override {
    resolve_ = {};
    resolve_.backgrounds = backgrounds_;
    last_ = builder_.build(config, settings_.offsets, fragments, settings_.policy, frame_attempts(settings_), &info_,
                           &resolve_);
    return last_;
  }

  vk::VulkanContext context_;
  vk::VulkanStreamBuilder builder_;  // the pipelines, compiled for the first frame
  std::vector<glm::vec3> backgrounds_;
  vk::VulkanResolve resolve_;
  vk::VulkanBuildInfo info_;
  TechniqueBuild last_;
};

class VulkanFrames final : public FramePath {
 public:
  VulkanFrames(const RenderSettings& s, gl::AtomicMode mode)
      : settings_(s), capture_(capture_config(s), s.offsets, mode, capture_options()), builder_(s) {}

  gl::GlFrameDriver& driver() override { return capture_; }

  void size_for(std::uint64_t fragments, RenderResult&) override { builder_.size_for(fragments); }

  void complete_frame(const gl::FrameReport&, SceneRenderer& renderer, FrameStats& fs, RenderResult& result) override {
    std::vector<Fragment> fragments = capture_.read_capture();
    result.backgrounds = renderer.read_opaque_colour();
    builder_.set_backgrounds(result.backgrounds);
    const TechniqueBuild& last = builder_.build(fragments, fs);
    result.growth_limited = result.growth_limited || last.growth_limited;
    if (last.too_deep) result.too_deep = last.too_deep;
    // The build's span is the device's (upload, gathers, sort, counters), the resolve's its own.
    fs.gather_ms = builder_.info().build_ms;
    fs.resolve_ms = builder_.resolved().resolve_ms;
    fs.deferred = builder_.info().deferred;
    fs.resume_rounds = builder_.info().resume_rounds;
    result.image = Image{settings_.config.screen, builder_.resolved().image};
    result.fragments = std::move(fragments);
  }

  void finish(SceneRenderer&, RenderResult& result) override {
    finish_cpu_result(settings_, builder_.release(), result);
    result.device = "vk " + builder_.info().atomic_mode + " (" + builder_.context().info().name +
                    "), fragments rasterized by gl (" + gl::query_gl_info().renderer + ")";
  }

 private:
  const RenderSettings& settings_;
  gl::GlHaBuffer capture_;
  VulkanFrameBuilder builder_;
};

}  // namespace

bool runs_on_path(RenderPath path, Technique technique) {
  return path != RenderPath::Vk || vk::runs_on_vulkan(technique);
}

void check_runs_on_path(RenderPath path, Technique technique) {
  if (!runs_on_path(path, technique))
    throw std::invalid_argument("the Vulkan path does not run " + to_string(technique) + " yet (it runs " +
                                vk::vulkan_technique_names() + ")");
}

std::unique_ptr<FramePath> make_vulkan_frames(const RenderSettings& settings, gl::AtomicMode mode) {
  return std::make_unique<VulkanFrames>(settings, mode);
}

}  // namespace habuffer
