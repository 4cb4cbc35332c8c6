#include "habuffer/extent.h"

#include <charconv>

namespace habuffer {

std::optional<Extent> parse_extent(std::string_view text) {
  auto x_pos = text.find('x');
  if (x_pos == std::string_view::npos) return std::nullopt;
  auto parse_side = [](std::string_view s) -> std::optional<std::uint32_t> {
    std::uint32_t v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || s.empty() || v == 0) return std::nullopt;
    return v;
  };
  auto w = parse_side(text.substr(0, x_pos));
  auto h = parse_side(text.substr(x_pos + 1));
  if (!w || !h) return std::nullopt;
  return Extent{*w, *h};
}

}  // namespace habuffer
