#include "habuffer/file_roles.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include "habuffer/atomic_file.h"
#include "habuffer/atomic_folder.h"
#include "habuffer/csv.h"
#include "habuffer/printable.h"

namespace habuffer {
namespace {

namespace fs = std::filesystem;

struct Identity {
  std::string resolved;
  std::optional<std::pair<dev_t, ino_t>> inode;  // where the file exists
  bool regular = false;
};

// The file a path writes or reads through its links (a dangling link's
// target included); the path itself for a loop of links.
std::string followed(const std::string& path) {
  try {
    return link_target(path);
  } catch (const DataError&) {
    return path;
  }
}

Identity identify(const std::string& path) {
  Identity id;
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(followed(path), ec), ec);
  id.resolved = ec ? path : resolved.string();
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.inode = std::make_pair(st.st_dev, st.st_ino);
    id.regular = S_ISREG(st.st_mode);
  }
  return id;
}

// Why `path` cannot be written, or empty: an existing file must be
// writable; a new one needs a writable parent directory (or, when the writer
// creates parents, a writable nearest existing ancestor).
std::string unwritable(const std::string& path, bool creates_parents) {
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (::access(path.c_str(), W_OK) != 0) return "is not writable";
    // A regular file is replaced by a temporary file written beside it
    // (habuffer/atomic_file.h): its directory must take new files.
    if (!fs::is_regular_file(path, ec)) return {};
    const fs::path dir = fs::path(fs::weakly_canonical(fs::absolute(path, ec), ec)).parent_path();
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      return "cannot be replaced: directory " + printable(dir.string()) +
             " is not writable (outputs are written beside the file and renamed over it)";
    return {};
  }
  fs::path dir = fs::absolute(path, ec).parent_path();
  if (!fs::is_directory(dir, ec)) {
    if (!creates_parents) return "cannot be created: directory " + printable(dir.string()) + " does not exist";
    while (!dir.empty() && dir != dir.root_path() && !fs::exists(dir, ec)) dir = dir.parent_path();
    if (!fs::is_directory(dir, ec)) return "cannot be created: " + printable(dir.string()) + " is not a directory";
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return "cannot be created: directory " + printable(dir.string()) + " is not writable";
  return {};
}

bool same_file(const Identity& a, const Identity& b) {
  if (a.inode && b.inode) return *a.inode == *b.inode;
  return a.resolved == b.resolved;
}

}  // namespace

FileRoles& FileRoles::input(std::string_view role, const std::string& path) {
  entries_.push_back({std::string(role), path, false, false, {}});
  return *this;
}

FileRoles& FileRoles::output(std::string_view role, const std::string& path, bool creates_parents) {
  entries_.push_back({std::string(role), path, true, creates_parents, {}});
  return *this;
}

FileRoles& FileRoles::output_set(std::string_view role, const std::string& folder, std::string_view members) {
  entries_.push_back({std::string(role), folder, true, false, std::string(members)});
  return *this;
}

namespace {

// Whether `inner` lies inside folder `outer` (both resolved; a link to a file
// inside counts, as the swap would take the file away from it).
bool inside(const std::string& inner, const std::string& outer) {
  const fs::path a(inner), b(outer);
  auto ai = a.begin();
  for (auto bi = b.begin(); bi != b.end(); ++bi, ++ai)
    if (ai == a.end() || *ai != *bi) return false;
  return true;
}

std::string resolved_fully(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(followed(path), ec), ec);
  return ec ? path : p.string();
}

}  // namespace

void FileRoles::check_sets() const {
  for (const Entry& set : entries_) {
    if (set.members.empty()) continue;
    if (const std::string why = output_set_conflict(set.path, set.members); !why.empty())
      throw FileConflict(set.role + ": " + why);
    const std::string folder = resolved_fully(set.path.size() > 1 && set.path.back() == '/' ? set.path.substr(0, set.path.find_last_not_of('/') + 1) : set.path);
    for (const Entry& e : entries_) {
      if (&e == &set) continue;
      const std::string other = resolved_fully(e.path);
      if (inside(other, folder))
        throw FileConflict(e.role + " " + printable(e.path) + " is inside " + set.role + " " + printable(set.path) +
                           (e.output ? " (the set replaces the folder whole)" : " (an input: the set would remove it)"));
      if (inside(folder, other))
        throw FileConflict(set.role + " " + printable(set.path) + " is inside " + e.role + " " + printable(e.path));
    }
  }
}

void FileRoles::check() const {
  check_sets();
  std::vector<Identity> ids;
  ids.reserve(entries_.size());
  for (const Entry& e : entries_) {
    if (!e.members.empty()) {  // an output set: checked above
      ids.push_back(identify(e.path));
      continue;
    }
    if (e.output && e.path.empty()) throw FileConflict(e.role + ": empty file name");
    if (e.output && fs::is_directory(e.path))
      throw FileConflict(e.role + ": " + printable(e.path) + " is a directory, not a file to write");
    if (e.output)
      if (const std::string why = unwritable(followed(e.path), e.creates_parents); !why.empty())
        throw FileConflict(e.role + ": " + printable(e.path) + " " + why);
    ids.push_back(identify(e.path));
  }
  for (std::size_t i = 0; i < entries_.size(); ++i)
    for (std::size_t j = i + 1; j < entries_.size(); ++j) {
      const Entry &a = entries_[i], &b = entries_[j];
      if (!a.output && !b.output) continue;  // reading a file twice harms nothing
      if (!same_file(ids[i], ids[j])) continue;
      // Devices such as /dev/null may take several outputs.
      if (a.output && b.output && ids[i].inode && !ids[i].regular) continue;
      const Entry& out = a.output ? a : b;
      const Entry& other = a.output ? b : a;
      throw FileConflict(out.role + " " + printable(out.path) + " is the same file as " + other.role +
                         (other.output ? " (two outputs)" : " (an input: it would be overwritten)"));
    }
}

void check_input_file(const std::string& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw DataError(printable(path) + ": cannot open for reading: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode))
    throw DataError(printable(path) + ": is a directory, not a " + std::string(what));
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw DataError(printable(path) + ": is a device or socket, not a " + std::string(what) +
                    " (only regular files and pipes are read)");
}

}  // namespace habuffer
