#include "habuffer/printable.h"

#include <algorithm>

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

std::string error_line(std::string_view what, std::size_t max_bytes) {
  std::string line;
  line.reserve(what.size());
  bool space = false;
  for (const char c : what) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
      space = !line.empty();
      continue;
    }
    if (space) line.push_back(' ');
    space = false;
    line.push_back(c);
  }
  // Text already quoted by excerpt() stays as it is (no second escaping of
  // its backslashes); a control byte left anywhere escapes the whole line.
  const bool control = std::any_of(line.begin(), line.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f;
  });
  if (control) return printable(line, max_bytes);
  if (line.size() <= max_bytes) return line;
  return line.substr(0, max_bytes) + "..." + full_length(line);
}

std::string filesystem_message(const std::filesystem::filesystem_error& e) {
  std::string_view what = e.what();
  constexpr std::string_view kPrefix = "filesystem error: ";
  if (what.substr(0, kPrefix.size()) == kPrefix) what.remove_prefix(kPrefix.size());
  // libstdc++ appends " [path1]" and " [path2]": the operation and reason come before.
  if (!e.path1().empty())
    if (const std::size_t at = what.find(" [" + e.path1().string() + "]"); at != std::string_view::npos)
      what = what.substr(0, at);
  std::string m = error_line(what, 200);
  if (!e.path1().empty()) {
    m += " (" + excerpt(e.path1().string(), 80);
    if (!e.path2().empty()) m += ", " + excerpt(e.path2().string(), 80);
    m += ")";
  }
  return m;
}

}  // namespace habuffer
