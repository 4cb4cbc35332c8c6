/// @file
/// The per-age offsets O[0..AMAX-1] of SPEC 3, shared by every pixel.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/extent.h"

namespace habuffer {

/// How offsets are made (SPEC 3): Random (uniform, seeded), Farthest (greedy
/// max-min toroidal distance, seeded) or List (given, an offsets file).
enum class OffsetGenerator { Random, Farthest, List };

/// The offsets O of one table, one per age (see above).
class OffsetSequence {
 public:
  /// `count` offsets (AMAX) for table `table`: pairwise distinct when the table
  /// has at least `count` slots, else the table's slots repeated cyclically.
  /// Every maker throws std::invalid_argument for a count of 0 or a table
  /// without slots (a zero side).
  static OffsetSequence random(Extent table, std::uint32_t count, std::uint64_t seed);
  /// Greedy max-min toroidal distance: each offset as far as possible from all
  /// earlier ones (ties: smallest slot index). The seed picks the first offset.
  static OffsetSequence farthest(Extent table, std::uint32_t count, std::uint64_t seed);
  /// Explicit offsets (an offsets file). Throws std::invalid_argument naming the
  /// offending row when an offset lies outside the table, offsets that must be
  /// distinct repeat, or fewer than min(count, table slots) rows are given.
  static OffsetSequence from_list(Extent table, std::uint32_t count, std::span<const glm::uvec2> rows);
  /// random() or farthest() by `gen`; throws std::invalid_argument for List, which
  /// must be given (from_list).
  static OffsetSequence make(OffsetGenerator gen, Extent table, std::uint32_t count, std::uint64_t seed);

  /// O[0..size()-1].
  [[nodiscard]] std::span<const glm::uvec2> values() const { return values_; }
  /// O[i], unchecked.
  [[nodiscard]] const glm::uvec2& operator[](std::size_t i) const { return values_[i]; }
  /// The number of offsets (`count`).
  [[nodiscard]] std::size_t size() const { return values_.size(); }
  /// The table the offsets were made for.
  [[nodiscard]] Extent table() const { return table_; }
  /// How the offsets were made.
  [[nodiscard]] OffsetGenerator generator() const { return generator_; }

 private:
  OffsetSequence(Extent table, OffsetGenerator gen, std::vector<glm::uvec2> distinct, std::uint32_t count);

  Extent table_;
  OffsetGenerator generator_;
  std::vector<glm::uvec2> values_;
};

/// Largest table (in slots) the exact farthest-point generator accepts: its
/// distance field holds 4 bytes per slot.
inline constexpr std::uint64_t kFarthestMaxSlots = std::uint64_t{1} << 28;

/// Squared toroidal distance between two cells of `table`.
std::uint64_t toroidal_distance2(glm::uvec2 a, glm::uvec2 b, Extent table);

/// Minimum pairwise toroidal distance among the first k offsets, for every
/// k = 2..n (result[k-2]); O(n^2).
std::vector<double> min_pairwise_distances(std::span<const glm::uvec2> offsets, Extent table);

/// The generator named "random" or "farthest" (what a command or a call
/// names; a list is given as rows, not by name); nullopt for anything else.
std::optional<OffsetGenerator> parse_offset_generator(std::string_view name);
/// "random", "farthest" or "list".
std::string to_string(OffsetGenerator gen);

}  // namespace habuffer
