#include "cli_args.h"

#include <algorithm>
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

std::string help_row(const std::string& left, const std::string& text) {
  constexpr std::size_t column = 30, width = 110;
  std::string out, line = left;
  if (line.size() + 2 > column) {
    out = line + "\n";
    line.clear();
  }
  line.resize(column, ' ');
  bool first = true;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!first && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line = std::string(column, ' ') + word;
    } else {
      line += (first ? "" : " ") + word;
    }
    first = false;
    start = end + 1;
  }
  return out + line + "\n";
}

std::string CommandSpec::help() const {
  std::string s = "usage: habuffer " + usage + "\n";
  for (const OptionSpec& o : options)
    s += help_row("  --" + o.name + (o.value.empty() ? "" : " " + o.value),
                   o.help + (o.fallback.empty() ? "" : " (default " + o.fallback + ")"));
  return s + notes;
}

const OptionSpec* CommandSpec::find(const std::string& name) const {
  for (const OptionSpec& o : options)
    if (o.name == name) return &o;
  return nullptr;
}

std::set<std::string> CommandSpec::valued() const {
  std::set<std::string> names;
  for (const OptionSpec& o : options)
    if (!o.value.empty()) names.insert(o.name);
  return names;
}

std::set<std::string> CommandSpec::flags() const {
  std::set<std::string> names;
  for (const OptionSpec& o : options)
    if (o.value.empty()) names.insert(o.name);
  return names;
}

std::vector<OptionSpec> operator+(std::vector<OptionSpec> a, const std::vector<OptionSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

bool print_help(const std::vector<std::string>& argv, const CommandSpec& spec) {
  return print_help(argv, spec.help());
}

Args::Args(const std::vector<std::string>& argv, const CommandSpec& spec) : Args(argv, spec.valued(), spec.flags()) {
  spec_ = &spec;
}

const std::string& Args::declared_default(const std::string& name) const {
  const OptionSpec* o = spec_ != nullptr ? spec_->find(name) : nullptr;
  if (o == nullptr) throw std::logic_error("option --" + name + " is not declared by the command");
  return o->fallback;
}

std::string Args::str(const std::string& name) const {
  const std::string& fallback = declared_default(name);
  return str(name, fallback);
}

std::uint64_t Args::u64_in(const std::string& name, std::uint64_t min, std::uint64_t max) const {
  const std::string text = str(name);
  return usage_errors(name, [&] { return parse_unsigned(text, min, max); });
}

std::uint32_t Args::u32_in(const std::string& name, std::uint32_t min, std::uint32_t max) const {
  return static_cast<std::uint32_t>(u64_in(name, min, max));
}

double Args::real(const std::string& name) const {
  const std::string text = str(name);
  return usage_errors(name, [&] { return parse_float64(text); });
}

std::vector<std::string> Args::list(const std::string& name) const { return list(name, declared_default(name)); }

Extent Args::size(const std::string& name) const {
  const std::string text = str(name);
  const std::optional<Extent> e = parse_extent(text);
  if (!e) throw UsageError("option --" + name + ": " + excerpt(text) + " is not a size WxH with positive sides");
  return *e;
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
  const std::string name = args.str("insert-order");
  const std::optional<InsertOrder> order = parse_insert_order(name);
  if (!order) throw UsageError("option --insert-order: '" + name + "' is not auto, arrival or pixel");
  return *order;
}

}  // namespace habuffer::cli
