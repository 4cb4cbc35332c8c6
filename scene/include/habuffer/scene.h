/// @file
/// A scene for `habuffer render`: triangle meshes, each drawn in one constant
/// colour and opacity (flat shaded), and how the camera should see it.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace habuffer {

/// Scenes that cannot be made (unknown name, unreadable file, no triangles).
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;  ///< takes the message
};

/// One triangle mesh in one colour and opacity.
struct Mesh {
  std::string name;                    ///< for messages
  std::vector<glm::vec3> positions;    ///< world space
  std::vector<std::uint32_t> indices;  ///< three per triangle
  glm::vec3 colour{0.8f};  ///< RGB in [0, 1]
  float opacity = 0.5f;  ///< 1: opaque, drawn with the depth test and never inserted
  /// With opacity 1: inserted like a translucent mesh instead of drawn in the
  /// opaque pass (seed 000's Fig. 2 measures opacity 1 through the A-buffer).
  bool insert_opaque = false;
  /// A mesh read from a file: the signed volume its own polygons enclose
  /// (before triangulation; polygon_triangulation.h), which references
  /// compare with instead of the triangles; NaN for generated meshes.
  double file_volume = std::numeric_limits<double>::quiet_NaN();

  /// Whether the opaque pass draws it (opacity 1 and not insert_opaque).
  [[nodiscard]] bool opaque() const { return opacity >= 1.0f && !insert_opaque; }
};

/// An axis-aligned box, empty until a point is added.
struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};     ///< smallest corner
  glm::vec3 hi{std::numeric_limits<float>::lowest()};  ///< largest corner
  /// Grows the box to hold `p`.
  void add(glm::vec3 p);
  /// Whether no point was added.
  [[nodiscard]] bool empty() const { return lo.x > hi.x; }
  /// The box's centre (meaningless when empty).
  [[nodiscard]] glm::vec3 centre() const { return (lo + hi) * 0.5f; }
};

/// Meshes and how to view them (see the file comment).
struct Scene {
  std::string name;          ///< the scene's name, or the mesh file's path
  std::vector<Mesh> meshes;  ///< drawn in this order (the planes scene's --order)
  /// Orthographic scenes (quads, planes) are seen along -z through the square
  /// [-half, half]^2 around the origin; others are framed in perspective.
  std::optional<float> orthographic_half;
  float default_yaw = 30.0f, default_pitch = 20.0f;  ///< degrees

  /// The box around every mesh's vertices.
  [[nodiscard]] Bounds bounds() const;
  /// Radius of the smallest sphere around `centre` holding every vertex
  /// (tighter than the box's half diagonal, which frames round scenes loosely).
  [[nodiscard]] float radius_around(glm::vec3 centre) const;
  /// Triangles of every mesh.
  [[nodiscard]] std::uint64_t triangle_count() const;
};

}  // namespace habuffer
