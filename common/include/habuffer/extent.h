/// @file
/// A 2D size in pixels, slots or cells, and its parsing from "WxH": the
/// vocabulary type every library of the project speaks (offsets, core, gl
/// and the tools above them), so it sits below all of them in habuffer::common
/// (header-only).
#pragma once

#include <charconv>
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
inline std::optional<Extent> parse_extent(std::string_view text) {
  const auto x_pos = text.find('x');
  if (x_pos == std::string_view::npos) return std::nullopt;
  const auto parse_side = [](std::string_view s) -> std::optional<std::uint32_t> {
    std::uint32_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || s.empty() || v == 0) return std::nullopt;
    return v;
  };
  const auto w = parse_side(text.substr(0, x_pos));
  const auto h = parse_side(text.substr(x_pos + 1));
  if (!w || !h) return std::nullopt;
  return Extent{*w, *h};
}

}  // namespace habuffer
