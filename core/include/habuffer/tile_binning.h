// Reorders a fragment stream by screen tile (a stable counting sort), so that
// threads inserting different tiles touch disjoint table regions: the
// coherent hash maps a screen tile at a given age onto one translated block
// of the table, so two threads on tiles far apart rarely share a cache line.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"

namespace habuffer {

struct TileBins {
  Extent tiles;                             // tile grid
  std::vector<Fragment> fragments;          // grouped by tile, row-major tiles, input order within a tile
  std::vector<std::uint64_t> tile_begin;    // tiles.area() + 1 prefix offsets into fragments
};

// tile: side in pixels, a power of two. Pixels must lie on the screen.
TileBins bin_by_tile(std::span<const Fragment> fragments, Extent screen, std::uint32_t tile, std::uint32_t threads);

// Cuts the tile sequence into runs of about `target` fragments each: the
// work units handed to threads. Returns run boundaries as tile indices
// (first 0, last tiles.area()).
std::vector<std::uint32_t> split_tiles(const TileBins& bins, std::uint64_t target);

}  // namespace habuffer
