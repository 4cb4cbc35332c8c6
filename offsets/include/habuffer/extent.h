/// @file
/// A 2D size in pixels, slots or cells, and its parsing from "WxH".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace habuffer {

struct Extent {
  std::uint32_t x = 0;
  std::uint32_t y = 0;

  [[nodiscard]] std::uint64_t area() const { return std::uint64_t{x} * y; }
  [[nodiscard]] std::string str() const { return std::to_string(x) + "x" + std::to_string(y); }
  friend bool operator==(const Extent&, const Extent&) = default;
};

/// Parses "WxH" with both sides positive decimal integers below 2^32.
std::optional<Extent> parse_extent(std::string_view text);

}  // namespace habuffer
