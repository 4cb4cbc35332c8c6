/// @file
/// The floors every technique is measured against, in the same run: one
/// atomic add per fragment (the least an A-buffer can do) and plain unsorted
/// blending (no lists at all). GL path: GlFloors (render library); CPU path:
/// the captured fragments through a per-pixel atomic counter and through the
/// `blend` technique's insertion. The CPU path adds the exact floor (issue
/// 36): bucket the fragments by pixel, sort each pixel's records, composite
/// from the buckets: the least any exact technique does, with no container
/// to keep between frames (ExactFloor).
#pragma once

#include <cstdint>
#include <memory>

#include "habuffer/harness/workload.h"
#include "habuffer/render/gl_floors.h"

namespace habuffer::harness {

/// One round's floors, wall-clock milliseconds.
struct Floors {
  double atomic_ms = 0.0;  ///< one atomic add per fragment
  double blend_ms = 0.0;   ///< plain unsorted blending
  double exact_ms = 0.0;   ///< CPU path: bucket, sort and composite (0 on the GL path: not measured)
};

/// The exact floor's work (see the file comment): a counting sort of the
/// fragments' records (depth code and colour, as every technique's lists
/// hold them) by pixel, each pixel's records sorted nearest first with
/// identical ones merged, and SPEC 7's float32 composite over each pixel's
/// background with the shared blend. The image equals every exact
/// technique's bit for bit (tests/test_harness.cpp); its buckets are kept
/// between calls, as techniques keep their containers.
class ExactFloor {
 public:
  /// The composited image of `fragments` (depths outside [0, 1] skipped, as
  /// every technique counts them invalid) over `backgrounds` (one per pixel
  /// of `screen`; std::invalid_argument otherwise), on `threads` threads
  /// (0: all) for the sort and composite; the bucketing runs on one.
  std::vector<glm::vec4> image(std::span<const Fragment> fragments, Extent screen,
                               std::span<const glm::vec3> backgrounds, std::uint32_t threads);

 private:
  std::vector<std::uint32_t> begin_;  // per pixel + 1: its first record
  std::vector<std::uint64_t> records_;
};

/// Measures a workload's floors on one path, round after round (see the file comment).
class FloorMeter {
 public:
  /// GL path: needs a current context and a scene (streams have no GL floor: std::invalid_argument).
  /// CPU path: uses `capture`'s fragments, which must outlive the meter.
  FloorMeter(const Workload& workload, const ExactCapture& capture, RenderPath path, std::uint32_t threads);
  /// Releases the GL floors (GL path).
  ~FloorMeter();
  FloorMeter(const FloorMeter&) = delete;
  FloorMeter& operator=(const FloorMeter&) = delete;

  /// One measurement of both floors.
  Floors measure();

 private:
  const ExactCapture& capture_;
  std::uint32_t threads_;
  ExactFloor exact_;
  std::unique_ptr<GlFloors> gl_;  // GL path only
};

/// Milliseconds of one atomic add per fragment to per-pixel counters on
/// `threads` threads (0: all).
double cpu_atomic_floor_ms(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads);

}  // namespace habuffer::harness
