/// @file
/// The exact transmittance reference of translucent shadows (issue 20): for
/// a receiving point, the segment to the light is intersected with every
/// triangle of the scene (a bounding-volume hierarchy of its own, built
/// here: median splits over triangle centroids), and (1 - alpha) of every
/// hit is multiplied in double. alpha is each mesh's opacity as the gather
/// packs it (round(opacity * 255) / 255; opaque meshes 1), every triangle
/// two-sided as the light pass rasterizes it. Hits nearer the receiver than
/// `self_distance` are its own surface and skipped.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/light_view.h"
#include "habuffer/scene.h"

namespace habuffer {

/// The reference over one scene (see the file comment).
class TransmittanceReference {
 public:
  /// Builds the hierarchy over every triangle of `scene`.
  explicit TransmittanceReference(const Scene& scene);

  /// T of the segment from `point` to `light` (to its position for a spot;
  /// against its direction past the scene's bounds for a directional light),
  /// in double. Hits at distance at most `self_distance` from `point` are
  /// skipped; throws std::invalid_argument for a negative or non-finite one.
  [[nodiscard]] double transmittance(glm::dvec3 point, const LightView& light, double self_distance) const;
  /// The same by testing every triangle (no hierarchy): what the tests hold it against.
  [[nodiscard]] double transmittance_brute_force(glm::dvec3 point, const LightView& light,
                                                 double self_distance) const;
  /// One crossing of the segment to the light.
  struct Hit {
    double distance;  ///< from the receiving point, along the segment
    double alpha;     ///< the triangle's opacity, as packed
    std::uint32_t triangle;  ///< which triangle: its index over the scene's meshes in order
    bool toward = false;     ///< the triangle faces the segment's far end (its winding, counter-clockwise, seen from there)
    std::uint32_t mesh = 0;  ///< the triangle's mesh (its index in the scene)
  };
  /// Every crossing of the segment from `point` to the light, nearest the
  /// point first (transmittance() is the product of 1 - alpha over those
  /// beyond self_distance).
  [[nodiscard]] std::vector<Hit> hits(glm::dvec3 point, const LightView& light) const;
  /// The same as crossings of surfaces: a segment through an edge or vertex
  /// meets every triangle there (the test is inclusive, and thin triangles
  /// round either way), so hits of one mesh and one facing within `same` of
  /// each other are one crossing (as a rasterizer covers one of them);
  /// other meshes' and opposite facings' stay (touching solids).
  [[nodiscard]] std::vector<Hit> crossings(glm::dvec3 point, const LightView& light, double same) const;
  /// Triangles in the hierarchy.
  [[nodiscard]] std::size_t triangles() const { return triangles_.size(); }

 private:
  struct Triangle {
    glm::dvec3 a, e1, e2;  // a vertex and the two edges from it
    double alpha;          // its mesh's opacity, as packed
    std::uint32_t id;      // its index over the scene's meshes in order (the hierarchy reorders)
    std::uint32_t mesh;    // its mesh
  };
  struct Node {
    glm::dvec3 lo, hi;          // bounds
    std::uint32_t first, count;  // leaf: triangles [first, first + count); inner: count 0, left child `first`
    std::uint32_t right;         // inner: the right child
  };
  struct Segment {
    glm::dvec3 origin, direction;  // direction unit length
    double length;
  };
  [[nodiscard]] Segment segment_to_light(glm::dvec3 point, const LightView& light) const;
  /// Calls visit(first, end) with each leaf's triangle range the segment's
  /// bounds meet, until it returns false.
  template <class Visit>
  void for_each_leaf(const Segment& s, Visit visit) const;
  /// The hit's distance along `s`, or a negative number for none.
  [[nodiscard]] static double hit(const Triangle& t, const Segment& s, bool* toward = nullptr);
  std::uint32_t build(std::uint32_t first, std::uint32_t count);

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
  glm::dvec3 scene_lo_{0.0}, scene_hi_{0.0};
};

}  // namespace habuffer
