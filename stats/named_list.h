// A list of names read as values, "all" meaning every one: the experiments'
// variant lists (probing, policy, offsets), read the same way by
// habuffer stats and the Python module. Private to the stats library.
#pragma once

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace habuffer::detail {

/// `items` as values of `names`, in order and without repeats ("all": every
/// name). Throws std::invalid_argument "unknown value 'X' (a, b or all)".
template <class T>
std::vector<T> named_list(const std::vector<std::string>& items, std::span<const std::pair<std::string_view, T>> names) {
  std::vector<T> out;
  for (const std::string& item : items) {
    bool found = false;
    for (const auto& [key, value] : names)
      if (item == key || item == "all") {
        if (std::find(out.begin(), out.end(), value) == out.end()) out.push_back(value);
        found = true;
      }
    if (found) continue;
    std::string known;
    for (const auto& n : names) known += std::string(n.first) + (&n == &names.back() ? " " : ", ");
    throw std::invalid_argument("unknown value '" + item.substr(0, 40) + (item.size() > 40 ? "...'" : "'") + " (" +
                                known + "or all)");
  }
  return out;
}

}  // namespace habuffer::detail
