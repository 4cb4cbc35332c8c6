/// @file
/// The CPU path's frames of one technique: the first size from a fragment
/// count, adaptive sizing between frames from the previous frame's exact
/// count (SPEC 8 on the HA-buffer's table and on the lists' pool), lossless
/// and automatic regathers, the container kept between frames of one size
/// (TechniqueFrames), and the frame's statistics. Private to the render
/// library (CpuFrames uses it).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "habuffer/lossless_build.h"
#include "habuffer/render/render_job.h"
#include "habuffer/technique_frames.h"

namespace habuffer {

/// Builds one technique's frames on the CPU (see the file comment).
class CpuBuilder {
 public:
  /// Keeps a reference to `settings`, which must outlive the builder.
  explicit CpuBuilder(const RenderSettings& settings);
  /// Sizes an automatic table or pool for `fragments` (before the first frame).
  void size_for(std::uint64_t fragments);
  /// One frame: inserts (and sorts) `fragments`, filling the frame's counts
  /// and gather time. The result stays here until the next frame or release().
  const TechniqueBuild& build(std::span<const Fragment> fragments, FrameStats& fs);
  /// The last frame's result and container (see TechniqueFrames::release).
  TechniqueBuild release() { return frames_.release(); }
  /// Containers made so far (1 when every frame kept the first).
  [[nodiscard]] std::uint64_t containers_made() const { return frames_.containers_made(); }

 private:
  const RenderSettings& settings_;
  TechniqueConfig config_;
  TechniqueFrames frames_;
  std::optional<std::uint64_t> previous_use_;  // stored records (HA) or nodes asked for (lists)
};


}  // namespace habuffer

namespace habuffer {
/// Moves the last frame's build into the result: the lists, the memory
/// (measured and by formula) and, when asked, the culled fragments per pixel
/// (the HA-buffer's early cull, replayed serially).
void finish_cpu_result(const RenderSettings& settings, TechniqueBuild last, RenderResult& result);
}  // namespace habuffer
