/// @file
/// How exact a light buffer's transmittance is: every receiving point of a
/// view (its transparent fragments and its opaque surface's pixels, world
/// points unprojected from pixel centres and depths) looked up in the light
/// buffer as the GPU does (the CPU path's walk, bit for bit the GPU's) and
/// against the ray-traced reference (TransmittanceReference, in double).
///
/// A light buffer samples the light's view at pixel centres and quantizes
/// depth into codes, so two bands of receivers may differ from the exact
/// segment by a whole record's alpha whatever the buffer; they are counted
/// and reported, and the error goal holds outside them:
/// - the silhouette band: the reference along the light pixel's centre ray
///   (at the receiver's light depth) differs from the reference at the
///   receiver's own point by more than 1/255 (an edge crosses the light
///   pixel, or a surface steeper than the bias rule's slope: those are
///   counted apart as self_shadow, the bias rule's residue);
/// - the silhouette band also takes receivers whose light pixel has an edge
///   within 1/128 pixel of its centre (the rasterizers snap vertices to
///   1/256 pixel, so coverage there is the rasterizer's, not the ray's);
/// - the depth band: along the light pixel's centre ray, some surface lies
///   within the rounding slack of the bias boundary (bias codes from the
///   receiver), where rounding decides whether it shadows, or two surfaces
///   in front lie within the slack of each other (at one code equal records
///   merge, SPEC 10; near that, rounding decides). The slack is four times
///   float32's rounding of the light's t, ulp(far) / (far - near) in codes
///   (t is an eye distance over the depth range), and at least 4 codes.
/// The reference skips, as the receiver's own surface, hits nearer than
/// bias + 1/2 codes (the lookup skips records within bias codes).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "habuffer/camera.h"
#include "habuffer/fragment.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/light_view.h"
#include "habuffer/record_layout.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer {

/// What measure_shadow_accuracy compares (borrowed).
struct ShadowReceivers {
  const Camera* camera = nullptr;        ///< the view's camera
  Extent screen;                         ///< its pixels
  std::span<const Fragment> transparent;  ///< the view's inserted fragments (x, y, depth t)
  std::span<const float> opaque_depth;   ///< per pixel, the opaque surface's t; 2 (or more) where none
};

/// The comparison's result (see the file comment).
struct ShadowAccuracy {
  std::uint64_t receivers = 0;        ///< receiving points checked
  std::uint32_t stride = 1;           ///< every stride-th receiver was checked
  std::uint64_t silhouette_band = 0;  ///< receivers in the silhouette band
  std::uint64_t depth_band = 0;       ///< receivers in the depth band
  std::uint64_t band = 0;             ///< in either
  /// Of the silhouette band: receivers whose own surface shadows them (the
  /// bias rule's measured residue: surfaces steeper than its slope).
  std::uint64_t self_shadow = 0;
  std::uint64_t within = 0;           ///< outside the bands, |T - T_ref| <= 1/255
  double within_fraction = 1.0;       ///< within / receivers outside the bands
  double rmse = 0.0, max_error = 0.0;  ///< over every receiver
  double rmse_outside = 0.0, max_error_outside = 0.0;  ///< outside the bands
  double ms = 0.0;                    ///< wall clock of the comparison
};

/// What the reference says at one receiver: where it falls in the light,
/// its exact T, and whether it lies in a band.
struct ShadowTruth {
  std::optional<LightSample> sample;  ///< nullopt: outside the light's frustum (lit)
  double reference = 1.0;             ///< T ray-traced in double
  bool silhouette = false, depth = false;  ///< in the silhouette band, the depth band
  bool self_shadow = false;  ///< its own surface crosses its light pixel's centre ray beyond the bias (steeper than the bias slope)
};
/// The truths at a view's receivers (every stride-th).
struct ShadowTruths {
  std::vector<ShadowTruth> at;
  std::uint32_t stride = 1;
  double ms = 0.0;  ///< wall clock of the ray tracing
};
/// A light buffer's T for a receiver where the light sees it.
using ShadowLookup = std::function<float(const LightSample& at)>;

/// The truths at `receivers` (every k-th for k = ceil(receivers /
/// max_receivers) when max_receivers is not 0): ray-traced once, scored for
/// any number of light buffers. `layout` and `bias` are the exact light
/// buffer's, whose codes fix the depth band. Throws std::invalid_argument
/// for receivers without a camera.
ShadowTruths shadow_truths(const TransmittanceReference& reference, const LightView& light, RecordLayout layout,
                           std::uint32_t bias, const ShadowReceivers& receivers, std::uint64_t max_receivers = 0);
/// `lookup` scored against `truths` (see ShadowAccuracy).
ShadowAccuracy score_shadows(const ShadowTruths& truths, const ShadowLookup& lookup);
/// The lookup of a light buffer that stores lists (habuffer/transmittance.h,
/// the GPU's walk), at the nearest light pixel or with `pcf` filtered over
/// 2x2 (transmittance_pcf); it borrows `light_buffer`. Throws
/// std::invalid_argument for L32 records.
ShadowLookup buffer_lookup(const FragmentBuffer& light_buffer, RecordLayout layout, std::uint32_t bias,
                           bool pcf = false);

/// Compares `light_buffer` (built from `light`, records of `layout`, looked
/// up with `bias` codes) with `reference` at every receiver, or at every
/// k-th for k = ceil(receivers / max_receivers) when max_receivers is not 0.
/// Throws std::invalid_argument for a buffer without lists or L32 records,
/// or receivers without a camera.
ShadowAccuracy measure_shadow_accuracy(const TransmittanceReference& reference, const LightView& light,
                                       const FragmentBuffer& light_buffer, RecordLayout layout, std::uint32_t bias,
                                       const ShadowReceivers& receivers, std::uint64_t max_receivers = 0,
                                       bool pcf = false);

}  // namespace habuffer
