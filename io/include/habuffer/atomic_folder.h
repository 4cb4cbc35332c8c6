/// @file
/// An output *set* (a folder of files, such as voxelize's PNG slices) that
/// appears whole or not at all, and never mixed with an earlier set.
///
/// The members are written into a temporary folder beside the target (same
/// file system). commit() swaps it in: a new target is a rename; an existing
/// one is exchanged with the temporary folder in one step (Linux
/// renameat2(RENAME_EXCHANGE)), and the earlier set, now under the temporary
/// name, is removed. So members of an earlier, larger set never stay behind,
/// and a signal (SIGINT, SIGTERM, SIGHUP with
/// remove_partial_outputs_on_signals(), habuffer/atomic_file.h) at any point
/// leaves either the earlier set or the new one, whole: the handler removes
/// whichever set sits under the temporary name.
///
/// A set never replaces what is not a set of its own kind: the target must be
/// missing, an empty folder, or a folder holding only files named like the
/// set's members (check_output_set, which FileRoles runs before any work). A
/// symbolic link to a folder keeps the link; the folder it names is replaced.
/// Sets are flat (no subfolders).
#pragma once

#include <string>
#include <string_view>

namespace habuffer {

/// Why `folder` cannot take a set whose member names match `members` (a glob
/// such as "slice_*.png"), or empty: a file that is not a folder, a folder
/// holding anything else (named, e.g. 'notes.txt'), or a parent that cannot
/// take the temporary folder.
std::string output_set_conflict(const std::string& folder, std::string_view members);

/// One output set written whole or not at all (see the file comment).
class AtomicFolder {
 public:
  /// Creates the temporary folder beside `folder`; DataError when it cannot
  /// or when `folder` cannot take the set (output_set_conflict).
  AtomicFolder(const std::string& folder, std::string_view members);
  /// Removes the temporary folder and what it holds unless commit() succeeded.
  ~AtomicFolder();
  AtomicFolder(const AtomicFolder&) = delete;
  AtomicFolder& operator=(const AtomicFolder&) = delete;

  /// Where member `name` is written now (inside the temporary folder); the
  /// name must match the members' glob.
  [[nodiscard]] std::string member(const std::string& name) const;
  /// Swaps the set in and removes the earlier one (see the file comment).
  void commit();
  /// The folder as given.
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  void discard() noexcept;
  std::string path_;     // as given
  std::string target_;   // through a link
  std::string members_;  // the glob
  std::string staging_;  // the temporary folder
  int slot_ = -1;        // in the signal-cleanup registry
  bool done_ = false;
};

}  // namespace habuffer
