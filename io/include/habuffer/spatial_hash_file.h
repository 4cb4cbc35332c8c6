/// @file
/// Files of the spatial hash (issue 22): key CSVs in and out, and the table
/// itself, saved and loaded whole.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::spatial {

/// Keys read from a CSV whose header is `x,y`, `x,y,z`, `x,y,value` or
/// `x,y,z,value` (decimal unsigned 32-bit fields; values also 0x hex).
struct KeyFile {
  std::vector<glm::uvec3> keys;
  std::vector<std::uint32_t> values;  ///< empty without a value column
  bool three_d = false;               ///< the file had a z column
};
/// Throws DataError naming the file, the line and the field.
KeyFile read_keys_csv(const std::string& path);
/// The keys' bounding domain: one more than the largest coordinate on each axis.
Domain domain_of(const std::vector<glm::uvec3>& keys);

/// The table file: "HASPATL1", then u32 fields (domain x y z, rule, age bits,
/// block, offsets generator, iteration limit, table x y), the u64 seed,
/// then the slots (u64 each) and the max-age cells (u32 each), all
/// little-endian. The offsets are made again from the generator, seed and
/// table. Written whole or not at all; throws DataError naming the path.
void save_spatial_hash(const std::string& path, const SpatialHash& table);
/// Reads and checks a table file (SpatialHash::restore's checks); throws
/// DataError naming the path and what is wrong.
SpatialHash load_spatial_hash(const std::string& path);
/// The same over the file's bytes (`name` in messages): what the fuzzer drives.
SpatialHash parse_spatial_hash(const std::string& bytes, const std::string& name);

}  // namespace habuffer::spatial
