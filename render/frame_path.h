/// @file
/// How `habuffer render` turns a gathered frame into an image, one class per
/// path: GpuFrames (the technique's buffers on the GPU, resolved there) and
/// CapturedFrames (the GPU only captures; a FrameBuilder builds and
/// composites on the CPU or a Vulkan device). The job
/// (render_job.cpp) draws and gathers the same way for both, so the paths
/// differ only behind this interface. Private to the render library.
#pragma once

#include <cstdint>
#include <memory>

#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/render/render_job.h"
#include "habuffer/render/scene_renderer.h"

namespace habuffer {

/// One render path's per-frame work (see the file comment); make_frame_path makes one.
class FramePath {
 public:
  /// Virtual: the job owns a path through this base.
  virtual ~FramePath() = default;
  /// The driver the scene renderer gathers into.
  virtual gl::GlFrameDriver& driver() = 0;
  /// Before the first frame: automatic sizes from the counting pass.
  virtual void size_for(std::uint64_t fragments, RenderResult& result) = 0;
  /// After the frame's gather: build or resolve, and fill the frame's stats
  /// (and, for the CPU path, the image).
  virtual void complete_frame(const gl::FrameReport& report, SceneRenderer& renderer, FrameStats& fs,
                              RenderResult& result) = 0;
  /// After the last frame: the image, lists, memory and device of the result.
  virtual void finish(SceneRenderer& renderer, RenderResult& result) = 0;
};

/// The path `settings.path` asks for (GpuFrames for RenderPath::Gl; CapturedFrames with the CPU's
/// or the Vulkan device's FrameBuilder for RenderPath::Cpu and Vk), its GL side in atomic mode `mode`.
std::unique_ptr<FramePath> make_frame_path(const RenderSettings& settings, gl::AtomicMode mode);

}  // namespace habuffer
