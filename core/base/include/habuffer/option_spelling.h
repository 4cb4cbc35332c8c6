/// @file
/// How the library's messages name an option the caller can change: as the
/// CLI's flag (--max-attempts 16) or as the Python module's keyword
/// (max_attempts=16). Option names are written as the CLI's, without the
/// dashes ("max-attempts").
#pragma once

#include <algorithm>
#include <string>
#include <string_view>

namespace habuffer {

/// The CLI's flags or the Python module's keywords.
enum class OptionSpelling {
  Flag,     ///< --max-attempts 16
  Keyword,  ///< max_attempts=16
};

/// "--max-attempts" or "max_attempts" for `name` "max-attempts".
inline std::string option_name(std::string_view name, OptionSpelling spelling) {
  std::string n(name);
  if (spelling == OptionSpelling::Flag) return "--" + n;
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

/// "--max-attempts 16" or "max_attempts=16".
inline std::string option_value(std::string_view name, const std::string& value, OptionSpelling spelling) {
  return option_name(name, spelling) + (spelling == OptionSpelling::Flag ? " " : "=") + value;
}

}  // namespace habuffer
