/// @file
/// Command-line options of one subcommand: "--name value" pairs and "--flag"
/// switches, checked against what the subcommand accepts.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/file_roles.h"
#include "habuffer/fragment_buffer.h"

namespace habuffer::cli {

/// Wrong use of the command line (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;  ///< takes the message
};

/// The shortest decimal that reads back as `v` ("1.1754944e-38").
std::string shortest(float v);
/// The same for double.
std::string shortest(double v);

/// `parse()`, a library rule's std::invalid_argument turned into bad usage:
/// "option --NAME: REASON", or the reason alone for an empty name (the
/// library's message names the option itself).
template <class Parse>
auto usage_errors(const std::string& name, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw UsageError(name.empty() ? std::string(e.what()) : "option --" + name + ": " + e.what());
  }
}

/// FileRoles::check, its conflicts as bad usage.
void check_files(const FileRoles& files);

/// Prints `usage` and returns true when the only argument is --help.
bool print_help(const std::vector<std::string>& argv, const char* usage);
/// The same for a help text assembled at run time (e.g. from the technique registry).
bool print_help(const std::vector<std::string>& argv, const std::string& usage);

/// What an option's value names on disk. Declared once with the option, so
/// that Args checks every command's files before its work (FileRoles: no
/// output over an input or another output, through links and hard links; no
/// input inside an output set) and a command cannot forget a file.
enum class FileRole {
  None,      ///< the value names no file
  Input,     ///< files the command reads
  Output,    ///< files the command writes (atomically, habuffer/atomic_file.h)
  OutputSet  ///< a folder the command fills with a set of files, swapped in whole (habuffer/atomic_folder.h)
};

/// How an option's value names files (see FileRole).
struct FileUse {
  FileRole role = FileRole::None;
  bool creates_parents = false;  ///< Output: the writer makes missing parent directories
  /// The files named by a value that is not simply one path (csg's solids,
  /// lists of scenes or meshes, "KIND:FILE"), none where it names only built-in
  /// things; null: the value is one path. Never throws: a value it cannot read
  /// is the command's own parser's to refuse.
  std::vector<std::string> (*paths)(const std::string& value) = nullptr;
  /// A value that names the one file "{}" (the role tests build values from it).
  const char* example = "{}";
  /// OutputSet: the members' names as a glob ("slice_*.png"); a folder that
  /// holds anything else is refused rather than replaced.
  const char* members = "";
};

FileUse reads();  ///< the value is one input file
/// Inputs named inside the value by `paths` (see FileUse).
FileUse reads_in(std::vector<std::string> (*paths)(const std::string&), const char* example);
FileUse writes();                  ///< the value is one output file in an existing directory
FileUse writes_creating_parents();  ///< the value is one output file; missing parent directories are made
/// Outputs named inside the value by `paths` (a list of tables, "KIND:FILE").
FileUse writes_in(std::vector<std::string> (*paths)(const std::string&), const char* example,
                  bool creates_parents = false);
FileUse writes_set(const char* members);  ///< the value is a folder of files named like `members`

/// One option of a command, declared once in the command's CommandSpec: the
/// accepted names, the help line, the default that parsing reads and the
/// files its value names all come from it.
struct OptionSpec {
  std::string name;      ///< --NAME
  std::string value;     ///< the value's shape in help ("WxH", "N"); empty for a switch (no value)
  std::string fallback;  ///< the default parsing reads (Args::str(name)) and help shows; empty: none
  std::string help;      ///< one phrase; where the default is not a constant, it says so in words
  FileUse files{};       ///< the files the value names, if any
};

/// A command's declaration: its usage line, its options, and the notes the
/// help prints after them.
struct CommandSpec {
  std::string usage;  ///< after "usage: habuffer ": the command and its required shape
  std::vector<OptionSpec> options;  ///< every option it accepts, in help order
  std::string notes;  ///< lines after the options, each "  ...\n"; may be empty

  /// "usage: ...", one line per option (its default added), then the notes.
  [[nodiscard]] std::string help() const;
  /// The option named `name`, or nullptr.
  [[nodiscard]] const OptionSpec* find(const std::string& name) const;
  /// Accepted names (valued, switches), as the set constructor of Args takes them.
  [[nodiscard]] std::set<std::string> valued() const;
  [[nodiscard]] std::set<std::string> flags() const;  ///< see valued()
};

/// One help row: `left` ("  --size WxH") padded to the help column, then
/// `text` wrapped at 110 columns (on the next line when `left` is too wide).
std::string help_row(const std::string& left, const std::string& text);

/// `a` then `b`: a command's own options and a shared group's.
std::vector<OptionSpec> operator+(std::vector<OptionSpec> a, const std::vector<OptionSpec>& b);

/// Prints `spec`'s help and returns true when the only argument is --help.
bool print_help(const std::vector<std::string>& argv, const CommandSpec& spec);

/// The files of `spec`'s options given in `args`, by their declared roles.
class Args;
FileRoles declared_files(const Args& args, const CommandSpec& spec);

/// One subcommand's parsed options (see the file comment).
///
/// Two rules hold for every command because they live here:
/// - the files its options name (OptionSpec::files) are checked together
///   before the command does anything (declared_files, FileRoles::check);
/// - an option given on the command line that the command never reads is a
///   bug (an option that silently does nothing): with HABUFFER_CHECK_OPTIONS=1
///   in the environment (the CLI tests set it), a command that returns
///   without reading one of its given options exits 70 naming it.
class Args {
 public:
  /// The options of `argv` by the names and defaults of `spec` (which must
  /// outlive the Args): its valued options and its switches. Throws
  /// UsageError on an unknown option, a missing value, a repeated option, or
  /// files in conflict (declared_files).
  Args(const std::vector<std::string>& argv, const CommandSpec& spec);
  /// Parses only, for a first look at options another Args reads (figure's
  /// options of every figure): no file check, no check of unread options.
  static Args probe(const std::vector<std::string>& argv, const CommandSpec& spec);
  ~Args();
  Args(const Args&) = delete;
  Args& operator=(const Args&) = delete;
  Args(Args&&) noexcept;
  Args& operator=(Args&&) = delete;

  /// Counts `names` as read: options whose values a probe of the same command
  /// line used already (demo's --load chose the table it adds to the line).
  void used_by_probe(std::initializer_list<const char*> names) const;
  /// Options given on the command line that nothing has read yet.
  [[nodiscard]] std::vector<std::string> unread() const;

  /// The value of `name`, or its declared default (CommandSpec; "" when it
  /// has none). std::logic_error for a name the command did not declare.
  [[nodiscard]] std::string str(const std::string& name) const;
  /// str(name), one of the alternatives its declaration names ("cpu|gl|vk"):
  /// UsageError "option --NAME: 'x' is not cpu, gl or vk" for anything else.
  [[nodiscard]] std::string choice(const std::string& name) const;
  /// str(name) as an unsigned integer in [min, max]; UsageError "option --NAME: ..." for bad text.
  [[nodiscard]] std::uint64_t u64_in(const std::string& name, std::uint64_t min = 0,
                                     std::uint64_t max = UINT64_MAX) const;
  /// As u64_in, for 32 bits.
  [[nodiscard]] std::uint32_t u32_in(const std::string& name, std::uint32_t min = 0,
                                     std::uint32_t max = UINT32_MAX) const;
  /// str(name) as a double (as real(name, fallback)).
  [[nodiscard]] double real(const std::string& name) const;
  /// str(name) as a comma-separated list (as list(name, fallback)).
  [[nodiscard]] std::vector<std::string> list(const std::string& name) const;
  /// str(name) as a size WxH with positive sides; UsageError for anything else.
  [[nodiscard]] Extent size(const std::string& name) const;

  /// Whether option or flag `name` was given.
  [[nodiscard]] bool has(const std::string& name) const;
  /// The value of `name`, or `fallback` when absent.
  [[nodiscard]] std::string str(const std::string& name, const std::string& fallback) const;
  /// The value of `name`; UsageError when absent.
  [[nodiscard]] std::string required(const std::string& name) const;
  /// An unsigned integer in [min, max], or `fallback` when absent; UsageError "option --NAME: ..." for bad text.
  [[nodiscard]] std::uint64_t u64(const std::string& name, std::uint64_t fallback, std::uint64_t min = 0,
                                  std::uint64_t max = UINT64_MAX) const;
  /// As u64, for 32 bits.
  [[nodiscard]] std::uint32_t u32(const std::string& name, std::uint32_t fallback, std::uint32_t min = 0,
                                  std::uint32_t max = UINT32_MAX) const;
  /// A double, or `fallback` when absent; UsageError for bad text (as parse_float64).
  [[nodiscard]] double real(const std::string& name, double fallback) const;
  /// A finite value parsed as the float32 it is used as (decimal rounded
  /// once); text beyond float32's range, or that rounds to zero from a
  /// non-zero value, is refused rather than turned into infinity or 0.
  [[nodiscard]] float f32(const std::string& name, float fallback) const;
  /// A comma-separated list; an empty list or an empty item is refused.
  [[nodiscard]] std::vector<std::string> list(const std::string& name, const std::string& fallback) const;
  /// Refuses each of `names` given on the command line unless `applies`:
  /// "option --NAME has no effect WHY".
  void refuse_unless(bool applies, std::initializer_list<const char*> names, const std::string& why) const;
  /// A size WxH with positive sides, or nullopt when absent; UsageError for anything else.
  [[nodiscard]] std::optional<Extent> extent(const std::string& name) const;

 private:
  // valued: options that take a value; flags: switches (see above).
  Args(const std::vector<std::string>& argv, const std::set<std::string>& valued, const std::set<std::string>& flags);
  [[nodiscard]] const std::string& declared_default(const std::string& name) const;
  // The value given for `name`, or nullptr; either way `name` counts as read.
  [[nodiscard]] const std::string* given(const std::string& name) const;

  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
  const CommandSpec* spec_ = nullptr;  ///< the declaration, when made from one
  mutable std::set<std::string> read_;  ///< names asked about (given or not)
  bool check_unread_ = false;  ///< check at destruction (see the class comment)
};

/// --insert-order auto|arrival|pixel (the HA-buffer's order on the CPU path;
/// InsertOrder): Auto when absent.
InsertOrder insert_order_option(const Args& args);

}  // namespace habuffer::cli
