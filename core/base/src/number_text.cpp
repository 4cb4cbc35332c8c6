#include "habuffer/number_text.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace habuffer {
namespace {

// Quoted text for messages: at most 40 bytes, unprintable bytes escaped.
std::string quoted(std::string_view text) {
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out + (text.size() > 40 ? "...'" : "'");
}

template <class T>
std::string shortest_of(T v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;
  return {buf, end};
}

template <class T>
T parse_finite(std::string_view text, const char* type) {
  T v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool whole = end == text.data() + text.size();
  if (ec == std::errc::result_out_of_range && whole)
    throw std::invalid_argument(quoted(text) + " is outside " + type + "'s range (it would become 0 or infinity; " +
                                "the smallest normal " + type + " is " + shortest_of(std::numeric_limits<T>::min()) +
                                ")");
  if (text.empty() || ec != std::errc() || !whole || !std::isfinite(v))
    throw std::invalid_argument(quoted(text) + " is not a finite number");
  return v;
}

}  // namespace

std::uint64_t parse_unsigned(std::string_view text, std::uint64_t min, std::uint64_t max) {
  const std::string range = std::to_string(min) + ".." + std::to_string(max);
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool whole = end == text.data() + text.size();
  if (ec == std::errc::result_out_of_range && whole)
    throw std::invalid_argument(quoted(text) + " is too large (accepted: " + range + ")");
  if (text.empty() || ec != std::errc() || !whole)
    throw std::invalid_argument(quoted(text) + " is not a non-negative integer (accepted: " + range + ")");
  if (v < min || v > max) throw std::invalid_argument(std::string(text) + " outside " + range);
  return v;
}

float parse_float32(std::string_view text) { return parse_finite<float>(text, "float32"); }
double parse_float64(std::string_view text) { return parse_finite<double>(text, "double"); }

std::string shortest_text(float v) { return shortest_of(v); }
std::string shortest_text(double v) { return shortest_of(v); }

}  // namespace habuffer
