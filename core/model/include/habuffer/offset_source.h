/// @file
/// Where a container's probe offsets come from (SPEC 4), for every table
/// size a build or a lossless regather (SPEC 8) tries.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/extent.h"
#include "habuffer/offset_sequence.h"

namespace habuffer {

/// Where the offsets of each attempt come from: a generator regenerated for
/// every table size (SPEC 8), or a fixed list, which stays valid for any
/// larger table since its offsets lie inside the first one.
struct OffsetSource {
  OffsetGenerator generator = OffsetGenerator::Random;  ///< random, farthest or list
  std::uint64_t seed = 1;  ///< for random and farthest
  std::vector<glm::uvec2> list;  ///< used when generator == List

  /// `count` offsets for `table`, generated or from `list` (OffsetSequence::from_list);
  /// throws std::invalid_argument as those do.
  [[nodiscard]] OffsetSequence make(Extent table, std::uint32_t count) const;
};

}  // namespace habuffer
