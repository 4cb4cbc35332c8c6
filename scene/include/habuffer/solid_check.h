/// @file
/// Whether a mesh bounds a solid: every edge shared by exactly two triangles
/// that run it in opposite directions (closed, manifold, consistently
/// oriented), and a non-zero enclosed volume. Vertices are welded by exact
/// position, so a mesh whose faces do not share vertex indices still counts
/// as closed. csg refuses a solid that fails; voxelize warns.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "habuffer/scene.h"

namespace habuffer {

/// What check_solid finds in one mesh.
struct SolidCheck {
  std::uint64_t boundary_edges = 0;      ///< edges of one triangle only: holes
  std::uint64_t non_manifold_edges = 0;  ///< edges of three or more triangles, or of two running it the same way
  std::uint64_t degenerate = 0;          ///< triangles with two corners at one point (ignored)
  double volume = 0.0;                   ///< the signed volume of its triangles
  /// Whether float32 can be why triangles collapsed: the mesh's extent is
  /// below 2^-16 of its largest coordinate, where float32 keeps fewer than
  /// 8 bits across it. Otherwise the file's own faces repeat a corner.
  bool float32_limited = false;
  /// Closed, manifold and consistently oriented.
  [[nodiscard]] bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
};

/// For each position, the index of the first position exactly equal to it
/// (bit patterns compared, -0 as +0), numbered in order of first
/// appearance: the weld the solid check and the mesh loader share.
std::vector<std::uint32_t> exact_vertex_ids(std::span<const glm::vec3> positions);

/// The edges and volume of `mesh` (see the file comment).
SolidCheck check_solid(const Mesh& mesh);

/// Why `mesh` does not bound a solid (one phrase: "has 3 open edges (holes)",
/// "encloses no volume"), or empty.
std::string solid_problem(const SolidCheck& check);

}  // namespace habuffer
