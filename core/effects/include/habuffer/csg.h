/// @file
/// CSG on sorted depth lists (seed 000, section 6.3): a pixel's records,
/// nearest first, each the crossing of one primitive's closed surface with
/// its facing, walked with one inside bit per primitive; the expression is
/// evaluated as the walk goes, and the pixel shows the first crossing where
/// it turns true. Any nesting of union, intersection and difference, no
/// expansion into a sum of products (OpenCSG's form), so the cost is one
/// evaluation per depth step whatever the expression.
///
/// A record's data word is primitive_id << 1 | exit (csg_data): an entry
/// and an exit at one depth are two records. Records at one depth code are
/// applied together before the expression is evaluated, so touching and
/// coplanar solids do not depend on the order records of one code come in:
/// A's exit and B's entry at one depth keep A | B true there (no surface
/// shows inside a union), A - B with B's entry at A's entry shows nothing.
/// Each crossing toggles its primitive's bit (parity, as the voxelizer's):
/// a triangle pair grazed near a silhouette cancels whichever facing the
/// rasterizer rounds it to (setting on entry and clearing on exit did not:
/// an exit rounded nearer than its entry left the primitive "inside" for
/// the rest of the list). The facing stays in the record so that an entry
/// and an exit at one depth are two records, not one merged (SPEC 10). The
/// camera is outside every primitive (every bit starts clear).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "habuffer/fragment_buffer.h"

namespace habuffer {

/// A CSG expression that cannot be parsed or evaluated: the message names
/// the token and its column (1-based).
class CsgError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;  ///< takes the message
};

/// The most primitives one expression may name (the inside bits of a pixel:
/// 64-bit words, bounded so a walk's state stays small).
inline constexpr std::uint32_t kMaxCsgPrimitives = 4096;

/// A record's data word for primitive `id` crossed entering (exit false) or leaving it.
constexpr std::uint32_t csg_data(std::uint32_t id, bool exit) { return id << 1 | (exit ? 1u : 0u); }

/// One inside bit per primitive.
class CsgInside {
 public:
  /// All clear, for `primitives` primitives.
  explicit CsgInside(std::uint32_t primitives) : words_((primitives + 63) / 64, 0) {}
  [[nodiscard]] bool test(std::uint32_t id) const { return (words_[id / 64] >> (id % 64)) & 1u; }
  void toggle(std::uint32_t id) { words_[id / 64] ^= std::uint64_t{1} << (id % 64); }
  void set(std::uint32_t id, bool on) {
    if (test(id) != on) toggle(id);
  }

 private:
  std::vector<std::uint64_t> words_;
};

/// A parsed expression over named primitives (see the file comment).
class CsgExpression {
 public:
  /// Parses `text`: primitive names (letters, digits, '_', starting with a
  /// letter or '_'), '|' or '+' union, '&' or '*' intersection, '-'
  /// difference, parentheses. '&' binds tighter than '|' and '-', which are
  /// left-associative at one level ("a - b | c" is "(a - b) | c"). Names
  /// are looked up in `primitives` (their ids are their indices). Throws
  /// CsgError naming the token and column: an unknown name, a missing
  /// operand or parenthesis, a stray character, an empty expression, more
  /// than kMaxCsgPrimitives primitives or nesting deeper than 1000.
  static CsgExpression parse(std::string_view text, std::span<const std::string> primitives);

  /// Whether a point inside exactly the primitives set in `inside` is in the solid.
  [[nodiscard]] bool evaluate(const CsgInside& inside) const;
  /// The primitives the expression was parsed against.
  [[nodiscard]] std::uint32_t primitives() const { return primitives_; }
  /// The expression with every operation parenthesized, by name ("((a - b) | c)").
  [[nodiscard]] const std::string& text() const { return canonical_; }

 private:
  enum class Op : std::uint8_t { Leaf, Union, Intersection, Difference };
  struct Step {
    Op op;
    std::uint32_t leaf;  // Leaf: the primitive
  };
  std::vector<Step> postfix_;
  std::uint32_t primitives_ = 0;
  std::string canonical_;
  friend class CsgParser;
};

/// What a pixel shows.
struct CsgSurface {
  bool visible = false;        ///< the expression turned true somewhere along the list
  std::uint32_t code = 0;      ///< the depth code where it did
  std::uint32_t primitive = 0; ///< the primitive whose crossing it was (the lowest id among records of that code)
  bool exit = false;           ///< that crossing left its primitive (a subtracted solid's far side shows)
};

/// Walks a pixel's records nearest first (codes falling) and returns the
/// first depth where `expression` turns true. Records' data words are
/// csg_data's. Records within `coincident` codes of the first of a run are
/// one depth: coplanar faces of different primitives, whose depths the GPU
/// rounds from different triangles a few codes apart, are applied together
/// (0: equal codes only). Throws CsgError for a primitive id beyond the
/// expression's.
CsgSurface csg_resolve(std::span<const ListEntry> nearest_first, const CsgExpression& expression,
                       std::uint32_t coincident = 0);

}  // namespace habuffer
