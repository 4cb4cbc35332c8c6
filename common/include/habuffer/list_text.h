/// @file
/// The one rule by which a list value is split ("a.obj,b.obj",
/// "planes:count=32"): at each separator not escaped by a backslash. "\,"
/// is a comma inside an item (a file named "a,b.obj" in a list is
/// "a\,b.obj"); a backslash before any other character stays as it is, so
/// that the item can be split again by another separator ("a\:b.obj:opacity=1"
/// inside a comma list keeps its "\:" for the word's own split).
///
/// Every parser of a list and every file-role reader of the same value calls
/// this, so the files a command checks are the files it reads.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace habuffer {

/// The items of `text` split at every unescaped `separator`, each "\"
/// + separator turned into the separator. An empty text gives one empty item.
inline std::vector<std::string> split_list(std::string_view text, char separator) {
  std::vector<std::string> items(1);
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\\' && i + 1 < text.size() && text[i + 1] == separator) {
      items.back() += separator;
      ++i;
    } else if (c == separator) {
      items.emplace_back();
    } else {
      items.back() += c;
    }
  }
  return items;
}

/// "a,b" → "a\,b": the text that split_list reads back as the one item `item`.
inline std::string escape_list_item(std::string_view item, char separator) {
  std::string out;
  for (const char c : item) {
    if (c == separator) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace habuffer
