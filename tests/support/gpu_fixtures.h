// Fixtures every GPU path's tests build from (one fixture, every path): the
// HA-buffer table cases of the bit-for-bit tests, and the offsets they use.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/offset_source.h"
#include "habuffer/technique.h"

namespace habuffer::test {

// A screen, its table, the age bits, the stream's shape and its load of the table.
struct TableCase {
  Extent screen, table;
  std::uint32_t age_bits;
  StreamKind kind;
  double load;
};

// Coherent and random streams, tables equal to and larger than the screen,
// 4 and 8 age bits, one case beyond a full table (ages fail).
inline std::vector<TableCase> gpu_table_cases() {
  return {TableCase{{32, 24}, {32, 24}, 8, StreamKind::Coherent, 0.8},
          TableCase{{40, 30}, {57, 41}, 4, StreamKind::Random, 0.6},
          TableCase{{64, 64}, {80, 64}, 8, StreamKind::Random, 0.9},
          TableCase{{16, 48}, {16, 48}, 4, StreamKind::Coherent, 1.1}};
}

inline OffsetSource seeded_random_offsets(std::uint64_t seed) {
  OffsetSource s;
  s.generator = OffsetGenerator::Random;
  s.seed = seed;
  return s;
}

}  // namespace habuffer::test
