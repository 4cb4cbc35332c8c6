/// @file
/// Frames of one technique on the CPU with its container kept between them
/// (issue 26). The paper keeps its table across frames and resizes it only
/// by the 80/30 rule; a fresh container per frame pays the page faults and
/// first touch of freshly mapped storage every frame (about 5 us per 4 KiB
/// page here) and, for the HA-buffer, a count of the old table on clear.
/// A frame whose configuration is the previous frame's reuses the container
/// (reset: zeroed, not counted); any other configuration (a table grown or
/// shrunk between frames, a lossless regrowth) makes a new one. The offsets'
/// source is fixed for all frames, so a kept HA-buffer always has the offsets
/// its table would get afresh, and a frame gives exactly what a fresh
/// container gives.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "habuffer/lossless_build.h"

namespace habuffer {

/// See above; move-only.
class TechniqueFrames {
 public:
  /// The offsets' source, the insertion options, the lossless policy and the
  /// attempts a frame may take (build_technique's).
  TechniqueFrames(OffsetSource offsets, InsertOptions options, ResizePolicy policy = {},
                  std::uint32_t max_attempts = 1);

  /// One frame of `config` over `fragments` by build_technique's rules,
  /// in the kept container where `config` is its configuration. The result
  /// stays here until the next frame or release().
  const TechniqueBuild& build(const TechniqueConfig& config, std::span<const Fragment> fragments);
  /// The last frame's result; throws std::logic_error before the first frame.
  [[nodiscard]] const TechniqueBuild& last() const;
  /// Hands the last frame's result (and its container) over; the next frame
  /// makes a new container. Throws std::logic_error before the first frame.
  TechniqueBuild release();
  /// Containers made so far: 1 for frames that all kept the first.
  [[nodiscard]] std::uint64_t containers_made() const { return made_; }

 private:
  std::unique_ptr<FragmentBuffer> container_for(const TechniqueConfig& c);

  OffsetSource offsets_;
  InsertOptions options_;
  ResizePolicy policy_;
  std::uint32_t max_attempts_;
  std::unique_ptr<TechniqueBuild> last_;
  std::uint64_t made_ = 0;
};

}  // namespace habuffer
