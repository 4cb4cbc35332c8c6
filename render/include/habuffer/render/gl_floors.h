/// @file
/// The two GL floors every technique is measured against, on a scene's
/// default view: one atomic add per transparent fragment, and plain unsorted
/// blending (SceneRenderer's floor passes over a fresh opaque pass). Used by
/// `habuffer bench` and the benchmarks alike, so both time the same passes.
#pragma once

#include <cstdint>

#include "habuffer/camera.h"
#include "habuffer/extent.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/render/scene_renderer.h"
#include "habuffer/scene.h"

namespace habuffer {

/// A scene's GL floor passes, ready to time (see the file comment).
class GlFloors {
 public:
  /// Needs a current context with 64-bit shader types (the gather module the
  /// renderer compiles); throws GlError without them. Runs each pass once, so
  /// llvmpipe's compile at the first draw is not part of a floor.
  GlFloors(const Scene& scene, Extent screen);

  /// Wall-clock milliseconds of one atomic-add pass (to glFinish), after a fresh opaque pass.
  double atomic_ms() { return pass(false); }
  /// Wall-clock milliseconds of one unsorted blending pass (to glFinish), after a fresh opaque pass.
  double blend_ms() { return pass(true); }
  /// Fragments the last atomic pass counted.
  [[nodiscard]] std::uint64_t fragments() { return renderer_.inserted(); }

 private:
  double pass(bool blend);

  Camera camera_;
  gl::GlHaBuffer module_owner_;  // the gather shader's module and uniform block
  SceneRenderer renderer_;
};

}  // namespace habuffer
