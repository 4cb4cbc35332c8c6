/// @file
/// Key sets and query orders of the spatial hash's experiments and
/// benchmarks (issue 22): the sparse image of Coherent Parallel Hashing's
/// demo (the non-background pixels of an image), a voxel surface, uniform
/// random keys; queried row-major, in Morton order, along a random walk or
/// shuffled. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::spatial {

/// Which keys.
enum class KeySet {
  SparseImage,  ///< discs of random radii over a 2D domain until `coverage` of its pixels are covered
  VoxelShell,   ///< the voxels within half a voxel of a sphere's surface in a cube domain
  Random,       ///< `count` distinct uniform keys of the domain
};
/// The order keys are visited in.
enum class KeyOrder {
  RowMajor,    ///< x fastest, then y, then z
  Morton,      ///< interleaved bits of x, y, z
  RandomWalk,  ///< a walk through the keys, each step to a nearby key (coherent, not ordered)
  Shuffled,    ///< uniformly shuffled
};

std::string to_string(KeySet set);
std::string to_string(KeyOrder order);
std::optional<KeySet> parse_key_set(const std::string& text);
std::optional<KeyOrder> parse_key_order(const std::string& text);

/// What to make.
struct KeySetOptions {
  KeySet set = KeySet::SparseImage;
  Domain domain{2048, 2048, 1};  ///< SparseImage, Random: 2D or 3D; VoxelShell: a cube (x = y = z)
  double coverage = 0.25;        ///< SparseImage: the share of pixels covered
  std::uint64_t count = 0;       ///< Random: keys
  std::uint64_t seed = 1;
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The keys, distinct, row-major.
std::vector<glm::uvec3> make_keys(const KeySetOptions& options);
/// `count` distinct keys of the domain not in `keys` (which must be row-major
/// and distinct), uniform; throws std::invalid_argument when the domain has
/// fewer free points.
std::vector<glm::uvec3> absent_keys(const std::vector<glm::uvec3>& keys, Domain domain, std::uint64_t count,
                                    std::uint64_t seed);
/// `keys` reordered.
std::vector<glm::uvec3> ordered(std::vector<glm::uvec3> keys, KeyOrder order, std::uint64_t seed);

}  // namespace habuffer::spatial
