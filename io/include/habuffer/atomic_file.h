/// @file
/// Outputs that appear whole or not at all.
///
/// Every file habuffer writes (lists and table CSVs, JSON stats and result
/// tables, images, heat maps) goes through an AtomicFile: the bytes go to a
/// temporary file beside the target (same directory, so the same file
/// system), which is flushed, fsync'd and renamed over the target only when
/// the writer commits. Whatever stops the writer first (an exception, a write
/// error such as a full disk or a file-size limit, a signal) leaves the
/// target as it was: an earlier 120 MB lists CSV is never replaced by a
/// partial one, and two runs writing one path leave one run's whole file.
///
/// Targets that are not regular files (/dev/null, /dev/stdout, a pipe) cannot
/// be replaced by a rename: they are written in place, and their write errors
/// (/dev/full: "No space left on device") are reported like any other.
///
/// A symbolic link as target keeps the link: the file it points to is
/// replaced, or created when the link dangles. A replaced file keeps its permission bits; a new one gets
/// 0666 less the umask, as a plain open would.
///
/// Signals: a process that can be interrupted while writing calls
/// remove_partial_outputs_on_signals() once (the habuffer CLI does): SIGINT,
/// SIGTERM and SIGHUP then remove every temporary file still open and exit
/// with 128 + the signal, and SIGXFSZ is ignored so that a file-size limit
/// becomes a write error ("File too large") instead of killing the process.
#pragma once

#include <string>
#include <string_view>

namespace habuffer {

/// One output written whole or not at all (see the file comment).
class AtomicFile {
 public:
  /// How the bytes reach the file.
  enum class Access {
    Stream,  ///< bytes come through write()
    ByName   ///< a library that opens files by name (OpenImageIO) writes staging_path() instead
  };

  /// Creates the temporary file (or, for a non-regular target, opens it in
  /// place: ByName then stages in the temporary directory). Throws DataError
  /// naming the path and the reason when it cannot.
  explicit AtomicFile(const std::string& path, Access access = Access::Stream);
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends bytes (Stream only); throws DataError "PATH: write failed: REASON".
  void write(std::string_view bytes);
  /// ByName only: the temporary file to write, which keeps the target's
  /// extension (file formats are chosen by it). Valid until commit().
  [[nodiscard]] const std::string& staging_path() const { return staging_; }
  /// ByName only: throws DataError ("PATH: write failed (the file-size
  /// limit is N bytes): File too large") when the staged file reached the
  /// process's file-size limit, which cut it there whatever the writing
  /// library said. commit() checks it; a caller that reads the staged file
  /// back first checks it before.
  void check_staged_size();
  /// Flushes, fsyncs and renames the temporary file over the target (or,
  /// for a non-regular target, copies what was staged into it). Throws
  /// DataError naming the reason; the target is then unchanged.
  void commit();
  /// The target as given.
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what, int error);
  void create_staging(const std::string& directory);
  void discard() noexcept;
  void copy_staged_into_target();
  std::string path_;     // as given (messages)
  std::string target_;   // resolved through a symbolic link
  std::string staging_;  // temporary file; empty when a Stream writes a device in place
  Access access_;
  int fd_ = -1;    // Stream: where write() goes
  int slot_ = -1;  // in the signal-cleanup registry
  bool in_place_ = false;
  bool done_ = false;
};

/// The file a path names after every symbolic link is followed, a dangling
/// link's target included (what writing through the link creates); the path
/// itself when it is no link. DataError for a loop of links.
std::string link_target(const std::string& path);

/// Installs the signal handlers described above (idempotent). Handlers the
/// process had for these signals are replaced.
void remove_partial_outputs_on_signals();

}  // namespace habuffer
