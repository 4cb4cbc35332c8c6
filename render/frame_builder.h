/// @file
/// The frames of one technique built from a captured stream: the first size
/// from a fragment count, adaptive sizing between frames from the previous
/// frame's exact count (SPEC 8 on the HA-buffer's table and on the lists'
/// pool), what a frame grew to kept for the next, and the frame's
/// statistics; the build itself is a subclass's: CpuFrameBuilder on the CPU
/// (lossless and automatic regathers, the container kept between frames of
/// one size: TechniqueFrames), the Vulkan path's in vulkan_frames.cpp.
/// Private to the render library (CpuFrames, VulkanFrames, render_job).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/lossless_build.h"
#include "habuffer/render/render_job.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/technique_frames.h"

namespace habuffer {

/// Sizes and counts one technique's frames (see the file comment).
class FrameBuilder {
 public:
  virtual ~FrameBuilder() = default;
  FrameBuilder(const FrameBuilder&) = delete;
  FrameBuilder& operator=(const FrameBuilder&) = delete;
  /// Sizes an automatic table or pool for `fragments` (before the first frame).
  void size_for(std::uint64_t fragments);
  /// One frame: inserts (and sorts) `fragments`, filling the frame's counts
  /// and gather time; `backgrounds` (one colour per pixel, kept by
  /// reference until image()) are what the frame is composited over. The
  /// result stays here until the next frame or release().
  const TechniqueBuild& build(std::span<const Fragment> fragments, std::span<const glm::vec3> backgrounds,
                              FrameStats& fs);
  /// The last frame's image over its backgrounds (SPEC 7); sets fs.resolve_ms.
  virtual std::vector<glm::vec4> image(FrameStats& fs) = 0;
  /// Where the frames are built and composited, for RenderResult::device.
  [[nodiscard]] virtual std::string device() const = 0;
  /// The last frame's result and container.
  virtual TechniqueBuild release() = 0;

 protected:
  /// Keeps a reference to `settings`, which must outlive the builder.
  explicit FrameBuilder(const RenderSettings& settings);
  /// One frame's build of `config`, lossless and automatic regathers by
  /// the settings (frame_attempts); the result stays in the subclass.
  virtual const TechniqueBuild& build_frame(const TechniqueConfig& config, std::span<const Fragment> fragments) = 0;
  const RenderSettings& settings_;
  std::span<const glm::vec3> backgrounds_;  // the frame's, while build_frame and image() run

 private:
  TechniqueConfig config_;
  std::optional<std::uint64_t> previous_use_;  // stored records (HA) or nodes asked for (lists)
};

/// The frames built on the CPU, the container kept between frames of one
/// size (TechniqueFrames).
class CpuFrameBuilder final : public FrameBuilder {
 public:
  /// Keeps a reference to `settings`, which must outlive the builder.
  explicit CpuFrameBuilder(const RenderSettings& settings);
  /// The last build composited on the CPU (FragmentBuffer::composite_image).
  std::vector<glm::vec4> image(FrameStats& fs) override;
  [[nodiscard]] std::string device() const override { return "cpu"; }
  /// The last frame's result and container (see TechniqueFrames::release).
  TechniqueBuild release() override { return frames_.release(); }

 private:
  const TechniqueBuild& build_frame(const TechniqueConfig& config, std::span<const Fragment> fragments) override {
    return *(last_ = &frames_.build(config, fragments));
  }
  TechniqueFrames frames_;
  const TechniqueBuild* last_ = nullptr;
};


}  // namespace habuffer

namespace habuffer {
/// The GL capture the CPU and Vulkan paths rasterize with: a screen-sized
/// HA-buffer that only captures (no early cull or saturation: the builder
/// culls), and its frame options.
BufferConfig capture_config(const RenderSettings& settings);
gl::GlFrameOptions capture_options();

/// Moves the last frame's build into the result: the lists, the memory
/// (measured and by formula) and, when asked, the culled fragments per pixel
/// (the HA-buffer's early cull, replayed serially).
void finish_cpu_result(const RenderSettings& settings, TechniqueBuild last, RenderResult& result);
}  // namespace habuffer
