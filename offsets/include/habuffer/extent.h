/// @file
/// A 2D size in pixels, slots or cells, and its parsing from "WxH".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace habuffer {

/// A 2D size: x columns by y rows of pixels, slots or cells.
struct Extent {
  std::uint32_t x = 0;  ///< width
  std::uint32_t y = 0;  ///< height

  /// x * y, in 64 bits.
  [[nodiscard]] std::uint64_t area() const { return std::uint64_t{x} * y; }
  /// "WxH", as parse_extent reads it.
  [[nodiscard]] std::string str() const { return std::to_string(x) + "x" + std::to_string(y); }
  /// Memberwise equality.
  friend bool operator==(const Extent&, const Extent&) = default;
};

/// Parses "WxH" with both sides positive decimal integers below 2^32.
std::optional<Extent> parse_extent(std::string_view text);

}  // namespace habuffer
