/// @file
/// The deepest pixel of a stream, in records.
///
/// The HA-buffer stores a pixel's records at distinct ages 1..AMAX (two
/// records of one pixel at one age would share a slot), so a pixel whose
/// fragments make more than AMAX = 2^A - 1 distinct records fails at any
/// table size: growing the table (lossless mode, automatic sizing) cannot
/// help, only more age bits (or another technique) can. Builds ask this
/// before growing in vain.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <glm/vec2.hpp>

#include "habuffer/extent.h"
#include "habuffer/buffer_config.h"
#include "habuffer/fragment.h"
#include "habuffer/option_spelling.h"
#include "habuffer/record_layout.h"
#include "habuffer/technique.h"

namespace habuffer {

/// A pixel and how many records its fragments make.
struct PixelDepth {
  glm::uvec2 pixel{0, 0};     ///< the pixel
  std::uint64_t records = 0;  ///< distinct records (identical records of a pixel merge, SPEC 10)
  /// False where only fragments were counted (duplicates included): a GPU
  /// counting pass, which sees no records.
  bool distinct = true;
};

/// The pixel with the most distinct records among those with more than
/// `limit`, or nothing when no pixel has more. Invalid fragments (SPEC 2)
/// make no record; fragments off `screen` are skipped. Linear in the
/// fragments, plus a sort of the fragments of pixels with more than `limit`.
std::optional<PixelDepth> pixel_deeper_than(std::span<const Fragment> fragments, Extent screen,
                                            const RecordLayout& layout, std::uint64_t limit);

/// The pixel with the most fragments by a count per pixel (row-major over
/// `screen`, as a counting pass gives), when that count exceeds `limit`;
/// nothing otherwise. Its `distinct` is false: duplicates are counted too.
std::optional<PixelDepth> pixel_counted_beyond(std::span<const std::uint32_t> counts, Extent screen,
                                               std::uint64_t limit);

/// Whether a count per pixel beyond AMAX (pixel_counted_beyond) means no
/// container of technique `t` under `c` can hold that pixel, so growing for
/// it is useless: a table (uses_table) without early cull, which could cull
/// some of those fragments. render's and habuffer-view's rule for stopping
/// lossless growth on the GPU path.
bool counted_depth_bounds_growth(Technique t, const BufferConfig& c);

/// The age bits whose AMAX holds `records` records per pixel, or nothing
/// when even HABUFFER_MAX_AGE_BITS cannot.
std::optional<std::uint32_t> age_bits_for(std::uint64_t records);

/// "pixel (3, 7) has 20 distinct fragments, more than AMAX = 2^4 - 1 = 15:
/// use --age-bits 5 (or accept the loss)" for messages; `spelling` Keyword
/// names the Python module's age_bits=5 instead.
std::string too_deep_message(const PixelDepth& deepest, std::uint32_t age_bits,
                             OptionSpelling spelling = OptionSpelling::Flag);

}  // namespace habuffer
