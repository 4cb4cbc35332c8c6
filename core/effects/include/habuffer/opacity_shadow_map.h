/// @file
/// The opacity shadow map (Kim and Neumann 2001), the baseline translucent
/// shadows are measured against: N planes across the light's depth range
/// (t = k / N, k = 0..N), and per light pixel and plane the transmittance of
/// everything in front of the plane, T_k = product of (1 - alpha) over the
/// pixel's fragments with t < k / N. A receiver at depth t between planes k
/// and k + 1 gets T interpolated linearly between T_k and T_{k+1}: fixed
/// memory (N + 1 floats per pixel) whatever the depth complexity, at the cost
/// of smearing every slice's opacity over the slice (its own surface shades
/// itself by the part of its slice in front of it, and nothing counts
/// exactly). The HA-buffer's lists are exact where this interpolates.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"

namespace habuffer {

/// An opacity shadow map (see the file comment).
class OpacityShadowMap {
 public:
  /// An empty map (T = 1 everywhere) of `size` pixels and `slices` slices.
  /// Throws std::invalid_argument for an empty size, slices outside
  /// 1..4096, or a map beyond 2^32 floats.
  OpacityShadowMap(Extent size, std::uint32_t slices);

  /// Adds fragments of the light's view (alpha: the rgba word's low byte
  /// over 255; depth t in [0, 1]). Throws std::out_of_range for a fragment
  /// off the map and std::invalid_argument for a depth outside [0, 1].
  void insert(std::span<const Fragment> fragments);
  /// T at pixel (x, y) for a receiver at depth t (clamped to [0, 1]).
  /// Throws std::out_of_range for a pixel off the map.
  [[nodiscard]] float transmittance(std::uint32_t x, std::uint32_t y, float t) const;

  /// The map's pixels.
  [[nodiscard]] Extent size() const { return size_; }
  /// Its slices N.
  [[nodiscard]] std::uint32_t slices() const { return slices_; }
  /// Bytes of its planes: (N + 1) floats per pixel.
  [[nodiscard]] std::uint64_t memory_bytes() const { return planes_.size() * sizeof(float); }

 private:
  // Plane k of pixel i at planes_[i * (N + 1) + k]: T in front of t = k / N.
  Extent size_;
  std::uint32_t slices_;
  std::vector<float> planes_;
};

}  // namespace habuffer
