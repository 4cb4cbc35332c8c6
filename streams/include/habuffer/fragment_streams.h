/// @file
/// Synthetic fragment streams, deterministic from their seed: the inputs of
/// benchmarks, property tests and the demo (real scenes come from the GL path),
/// reproducible on any machine without a GPU.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"
#include "habuffer/option_rules.h"  // table_for_load, which the streams' users size tables with

namespace habuffer {

/// The shape of a stream.
enum class StreamKind {
  Random,    ///< uniform random pixels, depths and colours: no coherence at all
  Coherent,  ///< rasterization-like: triangles and quads emitted primitive by primitive, in scanline order
  Stacked,   ///< the HA-buffer paper's Fig. 8: same-size quads at random depths, pulled together by `spread`
  Hot,       ///< uniform random pixels plus a few hot pixels of very high depth complexity
};

/// What make_stream makes.
struct StreamOptions {
  StreamKind kind = StreamKind::Coherent;  ///< the shape
  std::uint64_t count = 0;         ///< fragments
  std::uint64_t seed = 1;          ///< the same seed and options give the same stream
  std::uint32_t min_side = 4;      ///< coherent: primitive bounding-box side range, pixels
  std::uint32_t max_side = 64;     ///< coherent: the range's upper end (at least min_side)
  std::uint32_t alpha_min = 64;    ///< alpha byte range of colours, inclusive
  std::uint32_t alpha_max = 192;   ///< at most 255
  std::uint32_t quad_side = 32;    ///< stacked: side of every quad
  double spread = 1.0;             ///< stacked: 1 = quads anywhere, 0 = all exactly stacked at the centre
  std::uint32_t hot_pixels = 16;   ///< hot: how many hot pixels
  std::uint32_t hot_depth = 200;   ///< hot: fragments per hot pixel
};

/// options.count fragments on `screen`. Throws std::invalid_argument for an empty screen or options out of
/// range (sides, alpha, spread outside [0, 1], a zero quad side).
std::vector<Fragment> make_stream(Extent screen, const StreamOptions& options);


/// `layers` full-screen layers of distinct depths on `screen`, layer-major:
/// every pixel receives exactly `layers` fragments, its depths (k + 0.5) /
/// layers in the order k = (l + x + y + seed) mod layers (a rotation per
/// pixel), colours hashed from the seed: a scene whose depth complexity is
/// exactly `layers` (jumps and drops of adaptive sizing). Throws
/// std::invalid_argument for an empty screen or beyond 2^31 fragments.
std::vector<Fragment> layered_stream(Extent screen, std::uint32_t layers, std::uint32_t seed);

/// "random", "coherent", "stacked" or "hot"; throws std::invalid_argument otherwise.
StreamKind parse_stream_kind(const std::string& name);
/// The name parse_stream_kind reads.
std::string to_string(StreamKind kind);

}  // namespace habuffer
