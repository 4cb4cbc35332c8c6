/// @file
/// The floors every technique is measured against, in the same run: one
/// atomic add per fragment (the least an A-buffer can do) and plain unsorted
/// blending (no lists at all). GL path: GlFloors (render library); CPU path:
/// the captured fragments through a per-pixel atomic counter and through the
/// `blend` technique's insertion.
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
  std::unique_ptr<GlFloors> gl_;  // GL path only
};

/// Milliseconds of one atomic add per fragment to per-pixel counters on
/// `threads` threads (0: all).
double cpu_atomic_floor_ms(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads);

}  // namespace habuffer::harness
