/// @file
/// What a light buffer's depths mean (translucent shadows, shadow_lookup.h).
/// The lookup compares t, the light's eye distance linear between its near
/// and far planes (habuffer::LightView's depth, shared/ha_light_map.glsl).
/// The rasterizer gives a light pass window depth (gl_FragCoord.z), which is
/// t only for an orthographic light whose projection spans the same near and
/// far; under a perspective light it is a projective function of t. A frame
/// driver told its light (GlFrameOptions::light) stores t from either:
///
///   habuffer_insert_light(colour)                // t of gl_FragCoord.z through the light's projection
///   habuffer_insert_light(colour, eye_distance)  // t of the light's eye distance, the lookup's own formula
///   habuffer_insert_here(colour)                 // in such a driver, as habuffer_insert_light(colour)
///
/// and every frame records on its container what its depths are
/// (GlGatherDepth), which GlShadowLookup checks against its mapping.
#pragma once

#include <optional>
#include <string>

#include <glm/mat4x4.hpp>

namespace habuffer::gl {

/// How the light maps world points (habuffer::LightView's camera): the
/// view and projection matrices, the eye distances of t = 0 and 1, and the
/// map's pixels.
struct GlLightMapping {
  glm::mat4 view{1.0f};        ///< world to the light's eye space
  glm::mat4 projection{1.0f};  ///< eye to clip space
  float near_plane = 0.0f;     ///< eye distance of t = 0
  float far_plane = 1.0f;      ///< eye distance of t = 1
  /// Memberwise equality (the same light).
  friend bool operator==(const GlLightMapping&, const GlLightMapping&) = default;
};

/// How the rasterizer maps clip depth to window depth: glClipControl's depth
/// mode and glDepthRange.
struct GlWindowDepth {
  bool zero_to_one = false;  ///< GL_ZERO_TO_ONE (reversed-Z hosts); false: GL_NEGATIVE_ONE_TO_ONE, the default
  float range_near = 0.0f;   ///< glDepthRange's near value
  float range_far = 1.0f;    ///< glDepthRange's far value
  /// The current context's (needs one).
  static GlWindowDepth current();
  /// Memberwise equality.
  friend bool operator==(const GlWindowDepth&, const GlWindowDepth&) = default;
};

/// t of window depth z under a light: t = (a z + b) / (c z + d), the
/// inverse of the projection's depth and the window mapping composed with
/// t's linear map (a projective function: linear for an orthographic light,
/// c = 0). Coefficients are scaled so that max(|c|, |d|) = 1.
struct GlLightDepthMap {
  float a = 1.0f, b = 0.0f, c = 0.0f, d = 1.0f;
  /// t of window depth z, in float32 as the module's habuffer_light_depth computes it.
  [[nodiscard]] float operator()(float z) const { return (a * z + b) / (c * z + d); }
};

/// The map of `light` under `window`, computed in double from the
/// matrices' float entries and rounded to float. Throws
/// std::invalid_argument for a mapping whose near and far are not finite
/// with near < far, or whose projection's depth or w depends on the eye's x
/// or y (row 2 or 3 of columns 0 and 1 not zero), or that maps no window
/// depth to t (a degenerate depth row); GlError for an empty depth range.
GlLightDepthMap light_depth_map(const GlLightMapping& light, const GlWindowDepth& window);

/// What the depths of a frame's records are, recorded on the container by
/// the frame driver at every frame (GlTechnique::gather_depth): t of
/// `light` when the driver was told its light (GlFrameOptions::light), else
/// what habuffer_insert_here stores, window depth by the depth convention
/// (1 - z when `reversed`) under `window`.
struct GlGatherDepth {
  std::optional<GlLightMapping> light;  ///< the light whose t the records hold
  bool reversed = false;                ///< DepthConvention::Reversed: 1 - window depth
  GlWindowDepth window;                 ///< the window mapping at the frame
};

/// Whether a lookup through `mapping` reads records of `depth` correctly:
/// the same light (equal members), or, for window depth, a mapping whose t
/// is that window depth (an orthographic light whose projection spans
/// `mapping`'s near and far, as the stored value within 2^-22 at z = 0,
/// 1/2 and 1). Returns the one-line reason when it does not, empty when it does.
[[nodiscard]] std::string light_depth_mismatch(const GlGatherDepth& depth, const GlLightMapping& mapping);

}  // namespace habuffer::gl
