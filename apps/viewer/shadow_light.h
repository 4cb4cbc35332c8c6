/// @file
/// Translucent shadows in habuffer-view (seed 000, section 6), as a host
/// builds them with the installed API: a light buffer (gl::GlHaBuffer of L64
/// records, told its light through GlFrameOptions::light) gathered from a
/// spot along a direction with every mesh inserted (opaque ones at opacity
/// 1), and a gl::GlShadowLookup that the view's passes bind and call
/// (habuffer_shadow_transmittance, through R_SHADOWS in the shading). The
/// light and its bias follow `habuffer render --shadows` (spot_along,
/// frame_light, shadow_bias_codes), so both show the same image.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>

#include "gpu_meshes.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/light_view.h"
#include "view_passes.h"

namespace habuffer::view {

/// What the light pass built (for the panel).
struct LightFigures {
  Extent size, table;
  std::uint64_t fragments = 0, stored = 0, failures = 0;
  std::uint32_t attempts = 0, bias_codes = 0;
  double build_ms = 0.0;
};

class ShadowLight {
 public:
  /// The light buffer of `scene` lit along `direction` by a spot of 60 degrees
  /// with a map of `size` pixels, looked up by views whose module has
  /// `view_bindings`. Throws SceneError (a zero direction, an empty scene),
  /// std::invalid_argument or GlError (limits, no 64-bit records).
  ShadowLight(const Scene& scene, glm::vec3 direction, Extent size, const gl::GlBindings& view_bindings);
  ~ShadowLight();
  ShadowLight(const ShadowLight&) = delete;
  ShadowLight& operator=(const ShadowLight&) = delete;

  /// Gathers the light buffer (grown until nothing is dropped, at most 16 gathers).
  void build();
  /// Binds the light buffer and its block for the view's passes.
  void bind();
  [[nodiscard]] const gl::GlLightBindings& bindings() const { return lookup_->bindings(); }
  [[nodiscard]] const LightFigures& figures() const { return figures_; }
  [[nodiscard]] glm::vec3 direction() const { return direction_; }

 private:
  glm::vec3 direction_;
  LightView view_;
  GpuMeshes meshes_;  // every mesh inserted: opaque ones at opacity 1
  std::unique_ptr<gl::GlHaBuffer> buffer_;
  std::unique_ptr<ViewPasses> passes_;
  std::unique_ptr<gl::GlShadowLookup> lookup_;
  LightFigures figures_;
};

}  // namespace habuffer::view
