#include "habuffer/bounded_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "habuffer/data_error.h"
#include "habuffer/file_roles.h"
#include "habuffer/memory_budget.h"
#include "habuffer/printable.h"

namespace habuffer {
namespace {

constexpr std::size_t kChunk = std::size_t{1} << 20;

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  [[nodiscard]] int get() const { return fd_; }

 private:
  int fd_;
};

std::string article(std::string_view what) {
  const bool vowel = !what.empty() && std::string_view("aeiou").find(what.front()) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(what);
}

}  // namespace

std::string read_file_bounded(const std::string& path, std::string_view what, std::uint64_t max_bytes) {
  const std::string name = printable(path);
  // Missing, a directory, a device or a socket: refused before it is opened.
  check_input_file(path, what);
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) throw DataError(name + ": cannot open for reading: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw DataError(name + ": cannot read its size: " + std::strerror(errno));
  // The file opened is checked again: another may have taken the name since.
  if (S_ISDIR(st.st_mode)) throw DataError(name + ": is a directory, not " + article(what));
  const bool regular = S_ISREG(st.st_mode);
  if (!regular && !S_ISFIFO(st.st_mode))
    throw DataError(name + ": is a device or socket, not " + article(what) + " (only regular files and pipes are read)");
  const std::uint64_t memory = physical_memory_bytes();
  std::uint64_t limit = max_bytes;
  std::string beyond = "more than " + article(what) + " can be";
  if (regular) {
    const auto size = static_cast<std::uint64_t>(st.st_size);
    if (size > max_bytes)
      throw DataError(name + ": " + std::to_string(size) + " bytes, " + beyond + " (at most " +
                      std::to_string(max_bytes) + " bytes)");
    try {
      check_fits_in_memory(name + ": " + article(what) + " of " + std::to_string(size) + " bytes", size);
    } catch (const std::invalid_argument& e) {
      throw DataError(e.what());
    }
    if (memory != 0 && memory < limit) {
      limit = memory;
      beyond = "more than this machine's memory";
    }
  } else if (memory != 0 && memory / 2 < limit) {
    // A pipe's length is unknown: the buffer its bytes grow may hold twice them while it grows.
    limit = memory / 2;
    beyond = "more than half this machine's memory";
  }
  std::string bytes;
  if (regular) bytes.reserve(static_cast<std::size_t>(st.st_size) + 1);
  for (;;) {
    // Up to one byte past the limit: reading it shows the limit was passed.
    const std::size_t want =
        static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, limit + 1 - static_cast<std::uint64_t>(bytes.size())));
    const std::size_t old = bytes.size();
    bytes.resize(old + want);
    const ssize_t n = ::read(fd.get(), bytes.data() + old, want);
    if (n < 0) {
      const int error = errno;
      bytes.resize(old);
      if (error == EINTR) continue;
      throw DataError(name + ": read failed: " + std::strerror(error));
    }
    bytes.resize(old + static_cast<std::size_t>(n));
    if (n == 0) break;
    if (bytes.size() > limit)
      throw DataError(name + ": " + (regular ? "grew while read to more than " : "a pipe of more than ") +
                      std::to_string(limit) + " bytes, " + beyond);
  }
  return bytes;
}

}  // namespace habuffer
