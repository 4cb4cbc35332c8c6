#include "habuffer/atomic_folder.h"

#include <fcntl.h>
#include <fnmatch.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "habuffer/atomic_file.h"
#include "habuffer/csv.h"
#include "habuffer/printable.h"
#include "temporary_registry.h"

namespace habuffer {
namespace {

namespace fs = std::filesystem;

bool is_member(const std::string& name, std::string_view members) {
  return ::fnmatch(std::string(members).c_str(), name.c_str(), FNM_PERIOD) == 0;
}

// "out/slices/" names the folder "out/slices".
std::string without_trailing_slashes(std::string folder) {
  while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
  return folder;
}

}  // namespace

std::string output_set_conflict(const std::string& given, std::string_view members) {
  if (given.empty()) return "an empty folder name";
  const std::string folder = without_trailing_slashes(given);
  std::error_code ec;
  const fs::path target = link_target(folder);
  if (fs::exists(target, ec) && !fs::is_directory(target, ec))
    return printable(folder) + " is a file, not a folder for the set";
  if (fs::is_directory(target, ec)) {
    for (const fs::directory_entry& e : fs::directory_iterator(target, ec)) {
      const std::string name = e.path().filename().string();
      if (!is_member(name, members) || !e.is_regular_file(ec))
        return printable(folder) + " holds " + printable(name, 60) + ", which is not one of its " +
               std::string(members) + " files (give a new or empty folder: the set replaces the folder whole)";
    }
    if (ec) return printable(folder) + " cannot be listed: " + ec.message();
  }
  const fs::path parent = fs::absolute(target, ec).parent_path();
  if (!fs::is_directory(parent, ec)) return "cannot be created: directory " + printable(parent.string()) + " does not exist";
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
    return "cannot be created: directory " + printable(parent.string()) + " is not writable";
  return {};
}

AtomicFolder::AtomicFolder(const std::string& folder, std::string_view members)
    : path_(folder), members_(members) {
  if (const std::string why = output_set_conflict(folder, members); !why.empty())
    throw DataError(printable(folder) + ": " + why);
  std::error_code ec;
  target_ = without_trailing_slashes(fs::absolute(link_target(without_trailing_slashes(folder)), ec).lexically_normal().string());
  const fs::path t(target_);
  const Temporary staging = create_temporary(t.parent_path().string(), t.filename().string(), "", true, printable(folder));
  staging_ = staging.path;
  slot_ = staging.slot;
}

AtomicFolder::~AtomicFolder() {
  if (!done_) discard();
}

void AtomicFolder::discard() noexcept {
  if (!staging_.empty()) remove_flat_folder_now(staging_);
  unregister_temporary(slot_);
  slot_ = -1;
  done_ = true;
}

std::string AtomicFolder::member(const std::string& name) const {
  if (done_ || !is_member(name, members_) || name.find('/') != std::string::npos)
    throw std::logic_error("AtomicFolder::member: '" + name + "' is not one of " + members_ + " or the set is done");
  return staging_ + "/" + name;
}

void AtomicFolder::commit() {
  if (done_) throw std::logic_error("AtomicFolder::commit on " + path_ + ": already done");
  struct stat st {};
  if (::stat(target_.c_str(), &st) != 0) {
    if (::rename(staging_.c_str(), target_.c_str()) != 0) {
      const int error = errno;
      discard();
      throw DataError(printable(path_) + ": cannot move the set into place: " + std::strerror(error));
    }
    staging_.clear();
    discard();
    return;
  }
  // Checked again now: the folder may have changed since the command began.
  if (const std::string why = output_set_conflict(path_, members_); !why.empty()) {
    discard();
    throw DataError(printable(path_) + ": " + why);
  }
  (void)::chmod(staging_.c_str(), st.st_mode & 07777);
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
    const int error = errno;
    discard();
    throw DataError(printable(path_) + ": cannot swap the new set in: " + std::strerror(error));
  }
  discard();  // the earlier set, now under the temporary name
}

}  // namespace habuffer
