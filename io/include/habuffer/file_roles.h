/// @file
/// The files one command reads and writes, checked before any work is done:
/// an input must be a readable regular file or a pipe; no output may be one of
/// the inputs, and no two outputs may be the same file; every output must be
/// writable where it is (a typo in a directory fails at once, not after hours
/// of work). Paths are compared resolved (symbolic links, "..", relative to
/// the working directory) and, where the file exists, by device and inode
/// (hard links).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace habuffer {

/// Two roles that would clobber each other, or an output that cannot be a
/// file (empty name, a directory). The CLI reports it as bad usage.
class FileConflict : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;  ///< takes the message
};

/// The inputs and outputs of one command, declared then checked together (see the file comment).
class FileRoles {
 public:
  /// Declares an input; `role` names the option ("--in", "--heatmap depth") in messages. Returns *this.
  FileRoles& input(std::string_view role, const std::string& path);
  /// Declares an output (returns *this); creates_parents: the writer makes missing parent directories (images);
  /// otherwise the parent directory must exist.
  FileRoles& output(std::string_view role, const std::string& path, bool creates_parents = false);
  /// Declares an output set: a folder the command fills with files named like
  /// `members` (a glob), swapped in whole (habuffer/atomic_folder.h). Returns *this.
  FileRoles& output_set(std::string_view role, const std::string& folder, std::string_view members);
  /// Throws FileConflict for an output equal to an input or to another
  /// output, an empty output name, an output that is a directory, or one that
  /// cannot be written (a missing or read-only directory, a read-only file);
  /// for an input or output inside an output set's folder (the swap would
  /// remove it), a set's folder that is an input or output itself, or a
  /// folder the set cannot replace (output_set_conflict).
  void check() const;

 private:
  struct Entry {
    std::string role, path;
    bool output;
    bool creates_parents = false;
    std::string members;  ///< an output set's glob; empty for a file
  };
  void check_sets() const;
  std::vector<Entry> entries_;
};

/// Throws DataError unless `path` can be read as a stream: missing, a
/// directory, or anything but a regular file or a pipe (a device such as
/// /dev/zero never ends) is refused with the reason. `what` names the kind of
/// file ("CSV file", "image", "mesh").
void check_input_file(const std::string& path, std::string_view what);

}  // namespace habuffer
