/// @file
/// Polygons into triangles at any scale: ear clipping in the polygon's own
/// plane, in double precision, with orientation tests only (no absolute
/// epsilon), so a quad scaled by 1e-6 or 1e6 splits as it does at size 1.
/// (assimp's triangulation compares areas with fixed epsilons and breaks
/// closed meshes at small coordinates; habuffer's mesh loader triangulates
/// with this instead.)
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace habuffer {

/// Triangles (three indices each, appended to `out`) covering the simple
/// polygon `polygon` (indices into `positions`, in order, 3 or more). The
/// triangles keep the polygon's winding. A convex polygon gives the fan from
/// its first vertex ((0,1,2), (0,2,3), ...); a concave one its ears; a
/// degenerate or self-intersecting one still gives n - 2 triangles over its
/// vertices (their area is then what the polygon's outline allows).
void triangulate_polygon(std::span<const glm::vec3> positions, std::span<const std::uint32_t> polygon,
                         std::vector<std::uint32_t>& out);

/// The signed volume the closed surface of `polygons` encloses (each polygon
/// as indices, any vertex count), by the divergence theorem over each
/// polygon's own vertices (a fan from its first vertex): for planar polygons
/// the same whatever triangulation is chosen, so it checks a triangulation
/// without sharing its code.
/// `magnitude`, when given, receives the sum of the terms' magnitudes (the
/// scale its rounding is relative to).
double polygons_volume(std::span<const glm::vec3> positions, const std::vector<std::vector<std::uint32_t>>& polygons,
                       double* magnitude = nullptr);

/// The signed volume of a triangle list (three indices per triangle).
double triangles_volume(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices);

}  // namespace habuffer
