// The temporary files and folders that SIGINT, SIGTERM and SIGHUP remove
// (remove_partial_outputs_on_signals, habuffer/atomic_file.h); shared by
// AtomicFile and AtomicFolder, private to the io library.
#pragma once

#include <string>

namespace habuffer {

/// A slot for a temporary file, or -1 when the registry is full or the path
/// too long (the file is then only not removed on a signal).
int register_temporary(const std::string& path);
/// The same for a flat temporary folder: on a signal its files are removed, then it.
int register_temporary_folder(const std::string& path);
/// Frees a slot (-1: nothing).
void unregister_temporary(int slot);
/// Removes a flat folder's files and the folder (what a signal would do).
void remove_flat_folder_now(const std::string& path);

/// A temporary file or folder made by create_temporary: its path, its slot
/// in the registry, and (a file) its descriptor open for writing.
struct Temporary {
  std::string path;
  int slot = -1;
  int fd = -1;
};

/// Creates a fresh temporary in `directory` named ".STEM.XXXXXXXX.tmpSUFFIX"
/// (a random tag; up to 100 names tried), registered before it exists so a
/// signal between the two removes nothing: a file opened for writing
/// (O_EXCL), or with `folder` an empty folder. DataError "OWNER: cannot
/// create a temporary file (folder) in DIR: REASON" when it cannot.
Temporary create_temporary(const std::string& directory, const std::string& stem, const std::string& suffix,
                           bool folder, const std::string& owner);

}  // namespace habuffer
