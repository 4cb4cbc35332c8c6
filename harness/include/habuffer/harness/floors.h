// The floors every technique is measured against, in the same run: one
// atomic add per fragment (the least an A-buffer can do) and plain unsorted
// blending (no lists at all). GL path: the scene's transparent meshes drawn
// by SceneRenderer's floor passes; CPU path: the captured fragments through
// a per-pixel atomic counter and through the `blend` technique's insertion.
#pragma once

#include <cstdint>
#include <memory>

#include "habuffer/harness/workload.h"

namespace habuffer::harness {

struct Floors {
  double atomic_ms = 0.0;
  double blend_ms = 0.0;
};

class FloorMeter {
 public:
  // GL path: needs a current context and a scene (streams have no GL floor).
  FloorMeter(const Workload& workload, const ExactCapture& capture, RenderPath path, std::uint32_t threads);
  ~FloorMeter();
  FloorMeter(const FloorMeter&) = delete;
  FloorMeter& operator=(const FloorMeter&) = delete;

  Floors measure();

 private:
  struct Gl;
  const ExactCapture& capture_;
  std::uint32_t threads_;
  std::unique_ptr<Gl> gl_;
};

// Milliseconds of one atomic add per fragment to per-pixel counters on
// `threads` threads (0: all).
double cpu_atomic_floor_ms(std::span<const Fragment> fragments, Extent screen, std::uint32_t threads);

}  // namespace habuffer::harness
