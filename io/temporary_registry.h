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

}  // namespace habuffer
