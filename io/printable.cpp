#include "habuffer/printable.h"

namespace habuffer {
namespace {

std::string escaped(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const char ch : text) {
    const auto b = static_cast<unsigned char>(ch);
    if (b == '\\') {
      out += "\\\\";
    } else if (b < 0x20 || b >= 0x7F) {
      out += "\\x";
      out += kHex[b >> 4];
      out += kHex[b & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

std::string full_length(std::string_view text) { return " (" + std::to_string(text.size()) + " bytes)"; }

}  // namespace

std::string printable(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return escaped(text);
  return escaped(text.substr(0, max_bytes)) + "..." + full_length(text);
}

std::string excerpt(std::string_view text, std::size_t max_bytes) {
  std::string out(1, '\'');
  out.append(escaped(text.substr(0, max_bytes)));
  if (text.size() <= max_bytes) {
    out.push_back('\'');
  } else {
    out.append("...'");
    out.append(full_length(text));
  }
  return out;
}

}  // namespace habuffer
