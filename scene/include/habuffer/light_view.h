/// @file
/// The light of a translucent shadow map (seed 000, section 6): where it
/// shines from, the frustum fitted to the scene, and the mapping of a world
/// point to a light pixel and a depth t in [0, 1] (linear in the light's eye
/// depth, as Camera's), from which the light buffer is built and looked up
/// (habuffer/transmittance.h).
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "habuffer/camera.h"
#include "habuffer/extent.h"
#include "habuffer/scene.h"

namespace habuffer {

/// A light: directional (orthographic, parallel rays) or a spot
/// (perspective from `position`), and its map's resolution.
struct LightParams {
  /// directional: where the light shines, any finite vector but zero (scaled
  /// by its largest component before it is normalised, so no length
  /// overflows or underflows); a spot ignores it
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  bool orthographic = true;                 ///< directional; false: a spot at `position`
  glm::vec3 position{0.0f};                 ///< spot: the light's position, outside the scene's bounding sphere
  float fov = 60.0f;                        ///< spot: the cone's full angle in degrees, in (1, 179)
  Extent size{1024, 1024};                  ///< the light map's pixels (the light buffer's screen)
};

/// Where a world point falls in the light's view.
struct LightSample {
  glm::uvec2 pixel;  ///< the light pixel (window coordinates, floored)
  float depth;       ///< t in [0, 1]: 0 at the near plane, 1 at the far plane
  glm::vec2 window{0.0f};  ///< the window position, pixels (`pixel` is its floor): filtered lookups
};

/// A light framed on a scene (frame_light makes one).
struct LightView {
  Camera camera;  ///< the light's view and projection; near and far map to t = 0 and 1
  Extent size;    ///< the light map's pixels
  bool orthographic = true;  ///< directional light
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< where the light shines (unit length; a spot: toward the scene's centre)
  glm::vec3 position{0.0f};                ///< spot: where the light is

  /// The light pixel and depth of world point `p`; nullopt outside the
  /// frustum (beside the map, nearer than its near plane or beyond its far).
  [[nodiscard]] std::optional<LightSample> sample(glm::vec3 p) const;
  /// The world-space side of one light pixel at depth t (orthographic: the
  /// same everywhere), for the slope bias (see shadow_bias_codes).
  [[nodiscard]] float pixel_world_size(float t) const;
};

/// The light framed on `scene`: an orthographic frustum around the scene's
/// bounding sphere (directional), or a perspective one from `position`
/// whose cone holds the sphere (spot; `fov` is its upper limit), near and
/// far hugging the scene's extent along the light. Throws SceneError naming
/// the parameter for a zero or non-finite direction, an empty map, a fov
/// outside (1, 179) degrees, a spot inside the scene's bounding sphere or one
/// whose cone of `fov` cannot hold the scene, an empty scene, and a light
/// whose depth float32 cannot resolve: no depth range left between near and
/// far, or the precision rule (kLightDepthRounding): the light's depth
/// rounds by more than one light pixel's side at the far plane.
LightView frame_light(const Scene& scene, const LightParams& params);

/// The precision rule of frame_light. The light's depth is an eye distance
/// in float32, (view * p).z, whose terms reach `largest` = the largest of
/// the light's eye distance from the origin, the scene's farthest point from
/// it and the far plane; float32 rounds it by up to 4 ulps of that,
/// largest * 2^-21 world units (the float term of the accuracy check's
/// slack, render/shadow_accuracy.cpp). The bias rule (shadow_bias_codes)
/// covers the depth a slanted surface spans across one light pixel, not this
/// rounding: once the rounding exceeds one pixel's side at the far plane
/// (what a 45-degree surface spans, half the default bias), rounding alone
/// moves a receiver past its own surface's records and slanted surfaces
/// shadow themselves at random. frame_light refuses such a light, i.e.
/// `largest` beyond 2^21 light pixels' sides (about 2^21 * 2 r / map side
/// for a scene of radius r: 4200 r at 1024 pixels).
inline constexpr double kLightDepthRounding = 0x1.0p-21;

/// A spot shining along `direction` at the scene: on the line through the
/// bounding sphere's centre, at 1.5 times the distance where a cone of `fov`
/// degrees just holds the sphere (frame_light then narrows the cone to the
/// sphere). Throws SceneError like frame_light (direction, fov, size, an
/// empty scene).
LightParams spot_along(const Scene& scene, glm::vec3 direction, float fov, Extent size);

/// The bias in depth codes that keeps a surface's own records from shadowing
/// it: a surface at angle `theta` between its normal and the light's
/// direction moves in depth by tan(theta) * one light pixel's side across
/// the pixel, so `max_slope` (tan of the largest angle allowed) times that
/// side, over the depth range, in codes of `depth_bits`, plus one code for
/// rounding. Surfaces steeper than `max_slope` may shadow themselves.
/// Throws std::invalid_argument for a negative or non-finite `max_slope`, one
/// at least shadow_slope_limit(light.size), or depth bits outside 1..32.
std::uint32_t shadow_bias_codes(const LightView& light, float max_slope, std::uint32_t depth_bits);

/// The slope from which the bias rule leaves no shadow on a light map of
/// `size`: min(size.x, size.y). The bias is max_slope light pixels' sides
/// at the far plane (shadow_bias_codes); the map's short side at the far
/// plane, min(size) pixels, holds the scene's bounding sphere (frame_light),
/// so from that slope on the bias exceeds every depth between two surfaces
/// of the scene and no record is ever nearer than a receiver by more than
/// it: T = 1 everywhere. Slopes must be below it (a filter that doubles the
/// bias, pcf, below half of it).
double shadow_slope_limit(Extent size);

}  // namespace habuffer
