#include "cli_args.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "habuffer/list_text.h"
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
  // The list rule (habuffer/list_text.h), said wherever an option takes a list.
  const bool lists = std::any_of(options.begin(), options.end(),
                                 [](const OptionSpec& o) { return o.value.find(',') != std::string::npos; });
  if (lists) s += "  Lists are split at commas (scene words at ':' too); a file name holding one writes it \\, or \\:.\n";
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

FileUse reads() { return {FileRole::Input}; }
FileUse reads_in(std::vector<std::string> (*paths)(const std::string&), const char* example) {
  return {FileRole::Input, false, paths, example};
}
FileUse writes() { return {FileRole::Output}; }
FileUse writes_creating_parents() { return {FileRole::Output, true}; }
FileUse writes_in(std::vector<std::string> (*paths)(const std::string&), const char* example, bool creates_parents) {
  return {FileRole::Output, creates_parents, paths, example};
}
FileUse writes_set(const char* members) { return {FileRole::OutputSet, false, nullptr, "{}", members}; }

FileRoles declared_files(const Args& args, const CommandSpec& spec) {
  FileRoles files;
  for (const OptionSpec& o : spec.options) {
    const FileUse& use = o.files;
    if (use.role == FileRole::None || o.value.empty() || !args.has(o.name)) continue;
    const std::string value = args.str(o.name, "");
    const std::vector<std::string> paths = use.paths != nullptr ? use.paths(value) : std::vector<std::string>{value};
    const std::string role = "--" + o.name;
    for (const std::string& path : paths) {
      if (use.role == FileRole::Input) files.input(role, path);
      if (use.role == FileRole::Output) files.output(role, path, use.creates_parents);
      if (use.role == FileRole::OutputSet) files.output_set(role, path, use.members);
    }
  }
  return files;
}

Args::Args(const std::vector<std::string>& argv, const CommandSpec& spec) : Args(argv, spec.valued(), spec.flags()) {
  spec_ = &spec;
  check_files(declared_files(*this, spec));
  read_.clear();  // the file check reads values; the command must still read them itself
  const char* check = std::getenv("HABUFFER_CHECK_OPTIONS");
  check_unread_ = check != nullptr && std::string(check) == "1";
}

Args Args::probe(const std::vector<std::string>& argv, const CommandSpec& spec) {
  Args args(argv, spec.valued(), spec.flags());
  args.spec_ = &spec;
  return args;
}

Args::Args(Args&& other) noexcept
    : values_(std::move(other.values_)),
      flags_(std::move(other.flags_)),
      spec_(other.spec_),
      read_(std::move(other.read_)),
      check_unread_(other.check_unread_) {
  other.check_unread_ = false;
}

Args::~Args() {
  // Only a command that ran to its end: an error may stop it before it reads everything.
  if (!check_unread_ || std::uncaught_exceptions() > 0) return;
  const std::vector<std::string> names = unread();
  if (names.empty()) return;
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "--" : ", --") + n;
  std::fprintf(stderr, "habuffer: internal error: option %s given but never read by the command\n", list.c_str());
  std::fflush(stderr);
  std::_Exit(70);
}

void Args::used_by_probe(std::initializer_list<const char*> names) const {
  for (const char* n : names) read_.insert(n);
}

std::vector<std::string> Args::unread() const {
  std::vector<std::string> out;
  for (const auto& [name, value] : values_)
    if (read_.count(name) == 0) out.push_back(name);
  for (const std::string& name : flags_)
    if (read_.count(name) == 0) out.push_back(name);
  return out;
}

const std::string* Args::given(const std::string& name) const {
  read_.insert(name);
  const auto it = values_.find(name);
  return it == values_.end() ? nullptr : &it->second;
}

bool Args::has(const std::string& name) const {
  read_.insert(name);
  return values_.count(name) != 0 || flags_.count(name) != 0;
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

std::string Args::choice(const std::string& name) const {
  const OptionSpec* o = spec_ != nullptr ? spec_->find(name) : nullptr;
  if (o == nullptr || o->value.find('|') == std::string::npos)
    throw std::logic_error("option --" + name + " declares no alternatives");
  const std::string value = str(name);
  std::vector<std::string> alternatives;
  for (std::size_t start = 0;;) {
    const std::size_t bar = o->value.find('|', start);
    alternatives.push_back(o->value.substr(start, bar - start));
    if (bar == std::string::npos) break;
    start = bar + 1;
  }
  if (std::find(alternatives.begin(), alternatives.end(), value) != alternatives.end()) return value;
  std::string said;
  for (std::size_t i = 0; i < alternatives.size(); ++i)
    said += (i == 0 ? "" : i + 1 == alternatives.size() ? " or " : ", ") + alternatives[i];
  throw UsageError("option --" + name + ": '" + value + "' is not " + said);
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
  const std::string* v = given(name);
  return v == nullptr ? fallback : *v;
}

std::string Args::required(const std::string& name) const {
  const std::string* v = given(name);
  if (v == nullptr) throw UsageError("option --" + name + " is required");
  return *v;
}

std::uint64_t Args::u64(const std::string& name, std::uint64_t fallback, std::uint64_t min, std::uint64_t max) const {
  const std::string* v = given(name);
  if (v == nullptr) return fallback;
  return usage_errors(name, [&] { return parse_unsigned(*v, min, max); });
}

std::uint32_t Args::u32(const std::string& name, std::uint32_t fallback, std::uint32_t min, std::uint32_t max) const {
  return static_cast<std::uint32_t>(u64(name, fallback, min, max));
}

double Args::real(const std::string& name, double fallback) const {
  const std::string* v = given(name);
  return v == nullptr ? fallback : usage_errors(name, [&] { return parse_float64(*v); });
}

float Args::f32(const std::string& name, float fallback) const {
  const std::string* v = given(name);
  return v == nullptr ? fallback : usage_errors(name, [&] { return parse_float32(*v); });
}

std::vector<std::string> Args::list(const std::string& name, const std::string& fallback) const {
  const std::string text = str(name, fallback);
  std::vector<std::string> items = split_list(text, ',');
  for (const std::string& item : items)
    if (item.empty())
      throw UsageError("option --" + name + ": " + (text.empty() ? std::string("empty list") : "empty item in " + excerpt(text)));
  return items;
}

void Args::refuse_unless(bool applies, std::initializer_list<const char*> names, const std::string& why) const {
  if (applies) return;
  for (const char* n : names)
    if (has(n)) throw UsageError(std::string("option --") + n + " has no effect " + why);
}

std::optional<Extent> Args::extent(const std::string& name) const {
  const std::string* v = given(name);
  if (v == nullptr) return std::nullopt;
  auto e = parse_extent(*v);
  if (!e) throw UsageError("option --" + name + ": " + excerpt(*v) + " is not a size WxH with positive sides");
  return e;
}

InsertOrder insert_order_option(const Args& args) {
  const std::string name = args.str("insert-order");
  const std::optional<InsertOrder> order = parse_insert_order(name);
  if (!order) throw UsageError("option --insert-order: '" + name + "' is not auto, arrival or pixel");
  return *order;
}

}  // namespace habuffer::cli
