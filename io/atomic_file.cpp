#include "habuffer/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <random>

#include "habuffer/csv.h"
#include "habuffer/printable.h"
#include "temporary_registry.h"

namespace habuffer {
namespace {

namespace fs = std::filesystem;

// The temporary files and folders a signal handler removes. A handler may
// only use lock-free atomics and async-signal-safe calls (unlink, rmdir,
// _exit, raw system calls), so the registry is a fixed array of paths, each
// published by its state: 0 free, 1 being filled, 2 live file, 3 live folder.
struct Slot {
  std::atomic<int> state;
  std::array<char, 4096> path;
};
constexpr int kSlots = 256;
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "signal handlers need a lock-free slot state");

int register_path(const std::string& path, int live) {
  if (path.size() >= std::tuple_size_v<decltype(Slot::path)>) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) continue;
    std::memcpy(g_slots[i].path.data(), path.c_str(), path.size() + 1);
    g_slots[i].state.store(live, std::memory_order_release);
    return i;
  }
  return -1;
}

// A flat folder's files, then the folder, with raw system calls only
// (opendir and readdir may allocate; getdents64 does not).
void remove_flat_folder(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) char buffer[4096];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (long at = 0; at < n;) {
        struct Entry {
          std::uint64_t inode;
          std::int64_t offset;
          unsigned short length;
          unsigned char type;
          char name[1];
        };
        const auto* e = reinterpret_cast<const Entry*>(buffer + at);
        const bool dots = e->name[0] == '.' && (e->name[1] == '\0' || (e->name[1] == '.' && e->name[2] == '\0'));
        if (!dots) ::unlinkat(fd, e->name, 0);
        at += e->length;
      }
    }
    ::close(fd);
  }
  ::rmdir(path);
}

extern "C" void remove_temporaries_and_exit(int signal_number) {
  for (Slot& s : g_slots) {
    const int state = s.state.load(std::memory_order_acquire);
    if (state == 2) ::unlink(s.path.data());
    if (state == 3) remove_flat_folder(s.path.data());
  }
  ::_exit(128 + signal_number);
}

std::string random_tag() {
  static thread_local std::mt19937_64 rng{std::random_device{}() ^ static_cast<std::uint64_t>(::getpid())};
  constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::string tag(8, 'x');
  for (char& c : tag) c = kChars[rng() % (sizeof kChars - 1)];
  return tag;
}

}  // namespace

int register_temporary(const std::string& path) { return register_path(path, 2); }
int register_temporary_folder(const std::string& path) { return register_path(path, 3); }
void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0, std::memory_order_release);
}
void remove_flat_folder_now(const std::string& path) { remove_flat_folder(path.c_str()); }

Temporary create_temporary(const std::string& directory, const std::string& stem, const std::string& suffix,
                           bool folder, const std::string& owner) {
  const std::string dir = directory.empty() ? "." : directory;
  const char* kind = folder ? "folder" : "file";
  for (int attempt = 0; attempt < 100; ++attempt) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "." + string.
    std::string name(1, '.');
    name.append(stem).append(1, '.').append(random_tag()).append(".tmp").append(suffix);
    Temporary t;
    t.path = (fs::path(dir) / name).string();
    t.slot = folder ? register_temporary_folder(t.path) : register_temporary(t.path);
    const int made = folder ? ::mkdir(t.path.c_str(), 0777)
                            : (t.fd = ::open(t.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
    if (made >= 0) return t;
    const int error = errno;
    unregister_temporary(t.slot);
    if (error != EEXIST)
      throw DataError(owner + ": cannot create a temporary " + kind + " in " + printable(dir) + ": " +
                      std::strerror(error));
  }
  throw DataError(owner + ": cannot create a temporary " + kind + " in " + printable(dir) + ": 100 names taken");
}

namespace {


// write(2) until done: partial writes continue, EINTR retries.
int write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return 0;
}

// Makes a rename durable; a directory that cannot be opened or synced
// (some file systems) loses nothing but durability across a power cut.
void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string link_target(const std::string& path) {
  // Followed link by link (at most 40, as the kernel does): a dangling
  // link's target does not exist, so canonical() cannot resolve it, and
  // writing the link's own name would replace the link with a file.
  fs::path p = path;
  std::error_code ec;
  for (int hop = 0; hop < 40 && fs::is_symlink(p, ec); ++hop) {
    const fs::path next = fs::read_symlink(p, ec);
    if (ec) break;
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  if (fs::is_symlink(p, ec)) throw DataError(printable(path) + ": too many levels of symbolic links");
  const fs::path resolved = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? p.lexically_normal().string() : resolved.string();
}

AtomicFile::AtomicFile(const std::string& path, Access access) : path_(path), target_(path), access_(access) {
  if (path.empty()) throw DataError("empty output file name");
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;  // through links
  if (exists && S_ISDIR(st.st_mode)) throw DataError(printable(path_) + ": is a directory, not a file to write");
  // Devices and pipes (/dev/stdout is a link to one) are written in place,
  // by the name given; a link to a regular file (or to none yet) is
  // resolved, so the file it points to is replaced and the link kept.
  in_place_ = exists && !S_ISREG(st.st_mode);
  std::error_code ec;
  if (!in_place_ && fs::is_symlink(path, ec)) target_ = link_target(path);
  if (in_place_ && access_ == Access::Stream) {
    fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) fail("cannot open for writing", errno);
    return;
  }
  create_staging(in_place_ ? fs::temp_directory_path(ec).string() : fs::path(target_).parent_path().string());
  if (exists && !in_place_ && ::fchmod(fd_, st.st_mode & 07777) != 0) fail("cannot set the permissions of the temporary file", errno);
  if (access_ == Access::ByName) {
    ::close(fd_);
    fd_ = -1;
  }
}

void AtomicFile::create_staging(const std::string& directory) {
  // The extension as the caller named the file: a format chosen by name
  // (an image through a link to a device) must see the name given.
  const Temporary t = create_temporary(directory, fs::path(target_).stem().string(), fs::path(path_).extension().string(),
                                       false, printable(path_));
  staging_ = t.path;
  slot_ = t.slot;
  fd_ = t.fd;
}

AtomicFile::~AtomicFile() {
  if (!done_) discard();
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!staging_.empty()) ::unlink(staging_.c_str());
  unregister_temporary(slot_);
  slot_ = -1;
  done_ = true;
}

void AtomicFile::fail(const std::string& what, int error) {
  discard();
  throw DataError(printable(path_) + ": " + what + ": " + std::strerror(error));
}

void AtomicFile::write(std::string_view bytes) {
  if (done_ || fd_ < 0) throw std::logic_error("AtomicFile::write on " + path_ + ": not a stream or already done");
  if (const int error = write_all(fd_, bytes.data(), bytes.size()); error != 0) fail("write failed", error);
}

void AtomicFile::copy_staged_into_target() {
  const int in = ::open(staging_.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) fail("cannot read back the staged file", errno);
  const int out = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
  if (out < 0) {
    const int error = errno;
    ::close(in);
    fail("cannot open for writing", error);
  }
  std::array<char, 1 << 16> buffer{};
  int error = 0;
  for (;;) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n < 0) error = errno;
      break;
    }
    if ((error = write_all(out, buffer.data(), static_cast<std::size_t>(n))) != 0) break;
  }
  ::close(in);
  if (::close(out) != 0 && error == 0) error = errno;
  if (error != 0) fail("write failed", error);
}

void AtomicFile::check_staged_size() {
  // A library writing by name may ignore a write the file-size limit cut
  // (SIGXFSZ ignored: OpenImageIO's PNG writer reports success).
  struct stat st {};
  struct rlimit limit {};
  if (access_ == Access::ByName && !staging_.empty() && ::stat(staging_.c_str(), &st) == 0 &&
      ::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      static_cast<rlim_t>(st.st_size) >= limit.rlim_cur)
    fail("write failed (the file-size limit is " + std::to_string(limit.rlim_cur) + " bytes)", EFBIG);
}

void AtomicFile::commit() {
  if (done_) throw std::logic_error("AtomicFile::commit on " + path_ + ": already done");
  if (access_ == Access::ByName && in_place_) {
    copy_staged_into_target();
    discard();
    return;
  }
  if (access_ == Access::ByName) {
    fd_ = ::open(staging_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) fail("cannot reopen the temporary file", errno);
    check_staged_size();
  }
  // fsync before the rename: otherwise a crash can leave the new name on
  // an empty file. Devices and pipes (in place) need none.
  if (!in_place_ && ::fsync(fd_) != 0) fail("write failed", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("write failed", errno);
  if (in_place_) {
    done_ = true;
    return;
  }
  if (::rename(staging_.c_str(), target_.c_str()) != 0) fail("cannot replace the file", errno);
  staging_.clear();
  unregister_temporary(slot_);
  slot_ = -1;
  done_ = true;
  sync_directory(fs::path(target_).parent_path());
}

void remove_partial_outputs_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_exit;
  sigfillset(&action.sa_mask);  // one cleanup at a time
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &action, nullptr);
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGXFSZ, &ignore, nullptr);
}

}  // namespace habuffer
