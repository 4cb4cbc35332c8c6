/// @file
/// Closed triangle meshes of simple solids (CSG primitives, voxelization
/// tests): every triangle wound counter-clockwise seen from outside, every
/// edge shared by exactly two triangles, so a ray from outside crosses the
/// surface an even number of times.
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "habuffer/scene.h"

namespace habuffer {

/// The box [lo, hi] (12 triangles). Throws std::invalid_argument for a side not positive.
Mesh box_mesh(glm::vec3 lo, glm::vec3 hi, std::string name = "box");
/// A UV sphere of `slices` around and `stacks` pole to pole (at least 3 and
/// 2; its vertices on the sphere, so it lies inside it). Throws
/// std::invalid_argument for a radius not positive or too few segments.
Mesh sphere_mesh(glm::vec3 centre, float radius, std::uint32_t slices = 48, std::uint32_t stacks = 24,
                 std::string name = "sphere");
/// A closed cylinder along `axis` (unit length not required) from `base`
/// for `length`, radius `radius`, `sides` around (at least 3), with caps.
/// Throws std::invalid_argument for a radius or length not positive, a zero
/// axis or too few sides.
Mesh cylinder_mesh(glm::vec3 base, glm::vec3 axis, float length, float radius, std::uint32_t sides = 32,
                   std::string name = "cylinder");
/// A torus around the z axis through `centre`: ring radius `major`, tube
/// radius `minor` < major, `rings` x `sides` quads (each at least 3).
Mesh torus_mesh(glm::vec3 centre, float major, float minor, std::uint32_t rings = 48, std::uint32_t sides = 24,
                std::string name = "torus");

}  // namespace habuffer
