#include "cli_args.h"

#include <cstdio>

#include "habuffer/number_text.h"
#include "habuffer/printable.h"

namespace habuffer::cli {

std::string shortest(float v) { return shortest_text(v); }
std::string shortest(double v) { return shortest_text(v); }

void check_files(const FileRoles& files) {
  try {
    files.check();
  } catch (const FileConflict& e) {
    throw UsageError(e.what());
  }
}

bool print_help(const std::vector<std::string>& argv, const char* usage) {
  if (argv.size() != 1 || argv[0] != "--help") return false;
  std::fputs(usage, stdout);
  return true;
}

bool print_help(const std::vector<std::string>& argv, const std::string& usage) {
  return print_help(argv, usage.c_str());
}

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.rfind("--", 0) != 0) throw UsageError("unexpected argument " + excerpt(a));
    const std::string name = a.substr(2);
    if (flags.count(name) != 0) {
      if (!flags_.insert(name).second) throw UsageError("option --" + name + " given twice");
    } else if (valued.count(name) != 0) {
      if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
      if (!values_.emplace(name, argv[++i]).second) throw UsageError("option --" + name + " given twice");
    } else {
      throw UsageError("unknown option " + excerpt(a));
    }
  }
}

std::string Args::str(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

std::string Args::required(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw UsageError("option --" + name + " is required");
  return it->second;
}

std::uint64_t Args::u64(const std::string& name, std::uint64_t fallback, std::uint64_t min, std::uint64_t max) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  return usage_errors(name, [&] { return parse_unsigned(it->second, min, max); });
}

std::uint32_t Args::u32(const std::string& name, std::uint32_t fallback, std::uint32_t min, std::uint32_t max) const {
  return static_cast<std::uint32_t>(u64(name, fallback, min, max));
}

double Args::real(const std::string& name, double fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : usage_errors(name, [&] { return parse_float64(it->second); });
}

float Args::f32(const std::string& name, float fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : usage_errors(name, [&] { return parse_float32(it->second); });
}

std::vector<std::string> Args::list(const std::string& name, const std::string& fallback) const {
  const std::string text = str(name, fallback);
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (items.back().empty())
      throw UsageError("option --" + name + ": " + (text.empty() ? std::string("empty list") : "empty item in " + excerpt(text)));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

void Args::refuse_unless(bool applies, std::initializer_list<const char*> names, const std::string& why) const {
  if (applies) return;
  for (const char* n : names)
    if (has(n)) throw UsageError(std::string("option --") + n + " has no effect " + why);
}

std::optional<Extent> Args::extent(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  auto e = parse_extent(it->second);
  if (!e) throw UsageError("option --" + name + ": " + excerpt(it->second) + " is not a size WxH with positive sides");
  return e;
}

InsertOrder insert_order_option(const Args& args) {
  const std::string name = args.str("insert-order", "auto");
  const std::optional<InsertOrder> order = parse_insert_order(name);
  if (!order) throw UsageError("option --insert-order: '" + name + "' is not auto, arrival or pixel");
  return *order;
}

}  // namespace habuffer::cli
