/// @file
/// Lossless mode (SPEC 8, ours): a build that reports any failure is gathered
/// again into a grown table, a bounded number of times, so no fragment is ever
/// lost silently: either every fragment is accounted for without failure, or
/// the result says how many attempts failed and why.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/technique.h"
#include "habuffer/resize_policy.h"

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

/// One attempt of a build: its size, its counters and its capacity.
struct BuildAttempt {
  Extent table;  ///< the HA-buffer's table; zero for other techniques
  Counters counters;  ///< the attempt's counters
  std::uint64_t capacity = 0;  ///< records the technique could hold (slots, nodes, layers of every pixel)
};

/// An HA-buffer build: the final attempt's buffer and every attempt.
struct BuildResult {
  HaBuffer buffer;  ///< the final attempt's buffer
  Counters counters;                  ///< of the final attempt
  std::vector<BuildAttempt> attempts;  ///< every attempt, in order
  /// Lossless mode stopped without growing: this pixel has more distinct
  /// records than AMAX, which no table holds (TechniqueBuild::too_deep).
  std::optional<PixelDepth> too_deep;
  /// Whether the final attempt lost no fragment.
  [[nodiscard]] bool lossless() const { return counters.failures() == 0; }
};

/// One build (max_attempts = 1), or lossless mode: on failure grow the table by
/// `policy` and gather the whole stream again, at most `max_attempts` times.
BuildResult build(const BufferConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                  const InsertOptions& options, const ResizePolicy& policy = {}, std::uint32_t max_attempts = 1);

/// Any technique's build, lossless mode included: the HA-buffer's table grows
/// by `policy`; the linked lists' pool to at least the nodes the attempt asked
/// for (and by the policy's step); the fixed arrays' K to the most fragments a
/// pixel received.
struct TechniqueBuild {
  std::unique_ptr<FragmentBuffer> buffer;  ///< the final attempt's container
  Counters counters;                   ///< of the final attempt
  std::vector<BuildAttempt> attempts;  ///< every attempt, in order
  bool growth_limited = false;         ///< lossless mode stopped: the next size cannot be built
  /// HA-buffer: lossless mode stopped without growing because this pixel
  /// has more distinct records than AMAX (habuffer/pixel_depth.h): no table
  /// holds it.
  std::optional<PixelDepth> too_deep;
  /// Whether the final attempt lost no fragment.
  [[nodiscard]] bool lossless() const { return counters.failures() == 0; }
};

/// One build of any technique (max_attempts = 1), or lossless mode: on failure
/// grow the configuration (TechniqueConfig::grown) and gather the whole stream
/// again, at most `max_attempts` times, stopping early (growth_limited) when the
/// next size cannot be built, or (too_deep) when an HA-buffer's age failures
/// come from a pixel with more distinct records than AMAX, which no table holds. Throws std::invalid_argument for max_attempts 0 or
/// a bad policy or configuration, std::out_of_range for a fragment off the screen.
/// A pool_capacity of 0 (pool techniques) is the automatic pool: the
/// fragments at the policy's grow_at use (ResizePolicy::automatic), grown at
/// once when that drops (at least two attempts), as render's and the CLI's
/// --pool auto.
TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy = {}, std::uint32_t max_attempts = 1);

/// An HA-buffer's build (whose container's hash_table() is itself) as the
/// HA-buffer's BuildResult; throws std::invalid_argument naming the technique
/// for a build of another.
BuildResult ha_build_result(TechniqueBuild build);

/// HA-buffer without early cull (which could cull them): the pixel with the
/// most distinct records beyond AMAX, which fails at any table size
/// (habuffer/pixel_depth.h); nothing for other techniques or when none is.
std::optional<PixelDepth> pixel_beyond_every_table(const TechniqueConfig& config, std::span<const Fragment> fragments);

/// An empty container of the configured technique (offsets for the HA-buffer's table).
std::unique_ptr<FragmentBuffer> make_fragment_buffer(const TechniqueConfig& config, const OffsetSource& offsets);

}  // namespace habuffer
