#include "habuffer/tile_binning.h"

#include <bit>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace habuffer {

TileBins bin_by_tile(std::span<const Fragment> fragments, Extent screen, std::uint32_t tile, std::uint32_t threads) {
  if (tile == 0 || !std::has_single_bit(tile)) throw std::invalid_argument("tile side must be a power of two");
  const auto shift = static_cast<std::uint32_t>(std::countr_zero(tile));
  TileBins bins;
  bins.tiles = {(screen.x + tile - 1) >> shift, (screen.y + tile - 1) >> shift};
  const std::size_t n_tiles = bins.tiles.area();
  const std::uint32_t tiles_x = bins.tiles.x;
  auto tile_of = [&](const Fragment& f) { return (f.x >> shift) + (f.y >> shift) * tiles_x; };

  const std::size_t n = fragments.size();
  const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(threads, n / 4096 + 1));
  auto part_begin = [&](std::size_t p) { return n * p / parts; };
  // histogram[p * n_tiles + t]: fragments of part p in tile t, then turned
  // into each (part, tile)'s first output position.
  std::vector<std::uint64_t> histogram(parts * n_tiles, 0);
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t p) {
    std::uint64_t* h = histogram.data() + p * n_tiles;
    for (std::size_t i = part_begin(p); i < part_begin(p + 1); ++i) ++h[tile_of(fragments[i])];
  });
  bins.tile_begin.assign(n_tiles + 1, 0);
  std::uint64_t pos = 0;
  for (std::size_t t = 0; t < n_tiles; ++t) {
    bins.tile_begin[t] = pos;
    for (std::size_t p = 0; p < parts; ++p) {
      const std::uint64_t c = histogram[p * n_tiles + t];
      histogram[p * n_tiles + t] = pos;
      pos += c;
    }
  }
  bins.tile_begin[n_tiles] = pos;
  bins.fragments.resize(n);
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t p) {
    std::uint64_t* next = histogram.data() + p * n_tiles;
    for (std::size_t i = part_begin(p); i < part_begin(p + 1); ++i)
      bins.fragments[next[tile_of(fragments[i])]++] = fragments[i];
  });
  return bins;
}

std::vector<std::uint32_t> split_tiles(const TileBins& bins, std::uint64_t target) {
  const auto n_tiles = static_cast<std::uint32_t>(bins.tiles.area());
  std::vector<std::uint32_t> cuts{0};
  std::uint64_t run_start = 0;
  for (std::uint32_t t = 1; t < n_tiles; ++t) {
    if (bins.tile_begin[t] - run_start >= target) {
      cuts.push_back(t);
      run_start = bins.tile_begin[t];
    }
  }
  cuts.push_back(n_tiles);
  return cuts;
}

}  // namespace habuffer
