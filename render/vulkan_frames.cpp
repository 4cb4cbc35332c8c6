// The Vulkan path of `habuffer render`: over GL's capture (cpu_frames.cpp:
// CapturedFrames), the technique is built on a Vulkan device (lossless and
// automatic regathers there, by every path's rule) and resolved there over
// the opaque pass, so the image is the device's. The lists are read back
// for stats, dumps and heat maps.
#include <memory>

#include "frame_builder.h"
#include "frame_path.h"
#include "habuffer/vk/vulkan_build.h"
#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_registry.h"

namespace habuffer {
namespace {

// Each frame built and resolved on the device over the frame's backgrounds.
class VulkanFrameBuilder final : public FrameBuilder {
 public:
  explicit VulkanFrameBuilder(const RenderSettings& settings) : FrameBuilder(settings), builder_(context_) {}

  // The device's resolve of the last build; the frame's times are the
  // device's spans (upload, gathers, sort and counters; the resolve pass).
  std::vector<glm::vec4> image(FrameStats& fs) override {
    fs.gather_ms = info_.build_ms;
    fs.resolve_ms = resolve_.resolve_ms;
    fs.deferred = info_.deferred;
    fs.resume_rounds = info_.resume_rounds;
    return std::move(resolve_.image);
  }
  [[nodiscard]] std::string device() const override {
    return "vk " + info_.atomic_mode + " (" + context_.info().name + ")";
  }
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
  vk::VulkanResolve resolve_;
  vk::VulkanBuildInfo info_;
  TechniqueBuild last_;
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

std::unique_ptr<FrameBuilder> make_vulkan_frame_builder(const RenderSettings& settings) {
  return std::make_unique<VulkanFrameBuilder>(settings);
}

}  // namespace habuffer
