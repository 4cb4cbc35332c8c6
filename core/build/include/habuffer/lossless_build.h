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
#include "habuffer/data_error.h"
#include "habuffer/offset_source.h"
#include "habuffer/option_spelling.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/technique.h"
#include "habuffer/resize_policy.h"

namespace habuffer {

/// One attempt of a build: its size, its counters and its capacity.
struct BuildAttempt {
  Extent table;  ///< the HA-buffer's table; zero for other techniques
  Counters counters;  ///< the attempt's counters
  std::uint64_t capacity = 0;  ///< records the technique could hold (slots, nodes, layers of every pixel)
  /// The records (pool techniques: nodes) this attempt's size was computed
  /// for: the previous attempt's count (Counters::records_needed, the nodes
  /// it asked for) for a regather; 0 for a first attempt.
  std::uint64_t sized_for = 0;
  double ms = 0.0;  ///< wall time of the attempt (its gather, resume rounds and sort)
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
/// next size cannot be built, or (too_deep) where growing cannot help
/// (lossless_attempts: the rule of every path, the GPU's included). Returns
/// a lossy result as it is (require_lossless says why, for a caller that
/// asked for none). Throws std::invalid_argument for max_attempts 0 or
/// a bad policy or configuration, std::out_of_range for a fragment off the screen.
/// A pool_capacity of 0 (pool techniques) is the automatic pool: the
/// fragments at the policy's grow_at use (ResizePolicy::automatic), grown at
/// once when that drops (at least two attempts), as render's and the CLI's
/// --pool auto.
TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy = {}, std::uint32_t max_attempts = 1);

/// An HA-buffer's build (whose container as_hash_table() finds) as the
/// HA-buffer's BuildResult; throws std::invalid_argument naming the technique
/// for a build of another.
BuildResult ha_build_result(TechniqueBuild build);

/// HA-buffer without early cull (which could cull them): the pixel with the
/// most distinct records beyond AMAX, which fails at any table size
/// (habuffer/pixel_depth.h); nothing for other techniques or when none is.
std::optional<PixelDepth> pixel_beyond_every_table(const TechniqueConfig& config, std::span<const Fragment> fragments);

/// The attempts lossless mode may make for a stream (AttemptLimit::attempts)
/// and, when growing cannot help, why (too_deep).
struct AttemptLimit {
  std::uint32_t attempts = 1;  ///< at most this many attempts; 1: no growth
  /// An HA-buffer's pixel with more distinct records than AMAX, which no
  /// table holds (pixel_beyond_every_table): then attempts is 1.
  std::optional<PixelDepth> too_deep;
};

/// Lossless mode's rule, the one every path follows (build_technique and
/// TechniqueFrames on the CPU, build_technique_on_gl on the GPU, so the CLI
/// and the Python module): at most `max_attempts` attempts, each after a
/// failed one into a grown container, but no growth at all where growing
/// cannot help: an HA-buffer (without early cull) whose stream has a pixel
/// deeper than AMAX fails at every table size, whatever the attempts. Such
/// a stream fails every attempt, its first included, so asking before the
/// first attempt (the GPU, which cannot stop between its gathers) and after
/// a failed first one (the CPU, which then pays the look only on failure)
/// decide alike. `max_attempts` 1 (or 0, the callers' error) is returned
/// without looking at the stream.
AttemptLimit lossless_attempts(const TechniqueConfig& config, std::span<const Fragment> fragments,
                               std::uint32_t max_attempts);

/// A pixel's records and how many of them its list lacks.
struct PixelLoss {
  glm::uvec2 pixel{0, 0};     ///< the pixel
  std::uint64_t records = 0;  ///< its distinct valid records in the stream
  std::uint64_t lost = 0;     ///< of those, the ones its list does not hold
};

/// The pixel of `buffer`, built from `fragments`, that lost the most records
/// (the first in row-major order among equals): its distinct valid records
/// less those its list holds. Nothing when no pixel lost any, for a technique
/// that stores no lists, and with early cull (whose culled records are
/// hidden, not lost). Lists every pixel that received fragments: for
/// messages after a failed build, not for a loop.
std::optional<PixelLoss> pixel_most_lost(const FragmentBuffer& buffer, std::span<const Fragment> fragments);

/// Why a lossless build (of `fragments`, `max_attempts` allowed) still lost
/// fragments, as the tail of one line that names the attempts made, the
/// pixel that overflowed where known, AMAX (a hash table's techniques) and
/// what to change, spelled as `spelling` says:
///   " after 1 attempt: pixel (0, 0) has 300 distinct fragments, more than
///   AMAX = 2^8 - 1 = 255, at any table size: use --age-bits 9 (or accept the
///   loss); more attempts cannot help (--max-attempts 16)"
/// where growing cannot help (lossless_attempts), or
///   " after 16 attempts (last table 26x26; AMAX = 2^12 - 1 = 4095): pixel
///   (1, 2) lost the most, 3324 of its 4000 distinct records: raise
///   --max-attempts above 16"
/// (or, with growth_limited, that the next size cannot be built). Empty when
/// the build lost nothing.
std::string lossless_failure_reason(const TechniqueBuild& result, std::span<const Fragment> fragments,
                                    std::uint32_t max_attempts, OptionSpelling spelling = OptionSpelling::Flag);

/// A lossless request's end, the same for the library's callers (the CLI's
/// build-lists reports the same reason and exits 1; the Python module raises
/// habuffer.DataError): throws DataError "lossless mode: SUMMARY REASON"
/// (loss_summary, lossless_failure_reason) when `result` lost fragments.
void require_lossless(const TechniqueBuild& result, std::span<const Fragment> fragments, std::uint32_t max_attempts,
                      OptionSpelling spelling = OptionSpelling::Flag);

/// An empty container of the configured technique (offsets for the HA-buffer's table).
std::unique_ptr<FragmentBuffer> make_fragment_buffer(const TechniqueConfig& config, const OffsetSource& offsets);

}  // namespace habuffer
