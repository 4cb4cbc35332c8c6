#include "habuffer/fenced_call.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "habuffer/data_error.h"
#include "habuffer/memory_budget.h"

// A sanitizer runtime's (ASan, UBSan, TSan): absent (null) in a build
// without one.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace habuffer {
namespace {

// Writes all of `data` to `fd`; false on an error (the parent has gone).
bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The child: runs `work`, writes a status byte ('+' result, '!' message) and
// the bytes, and leaves without the parent's exit handlers.
[[noreturn]] void run_child(const std::string& what, int fd, const std::function<std::string()>& work,
                            const FenceLimits& limits) {
  for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) std::signal(s, SIG_DFL);
  // A fault or a limit ends the child as the kernel ends it, whatever the
  // parent installed: a host's crash reporter (or libFuzzer's, or a
  // sanitizer's) would otherwise report the reader's crash as its own, write
  // files, or catch RLIMIT_CPU's SIGXCPU and keep the child running.
  for (const int s : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGXCPU, SIGXFSZ}) std::signal(s, SIG_DFL);
  // The same for a sanitizer's death callback (libFuzzer writes its input as
  // a crash file there): where a sanitizer runtime is linked, none is left.
  if (__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
  // What the third-party code prints as it dies (glibc's "malloc(): invalid
  // size") is not ours to show: the parent says it in one line.
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
  rlimit cpu{};
  if (::getrlimit(RLIMIT_CPU, &cpu) == 0 && (cpu.rlim_max == RLIM_INFINITY || limits.cpu_seconds < cpu.rlim_max)) {
    cpu.rlim_cur = limits.cpu_seconds;
    ::setrlimit(RLIMIT_CPU, &cpu);
  }
  // New data memory (RLIMIT_DATA counts private writable mappings: the heap,
  // mmap'd blocks, and under the sanitizers their allocators' chunks too) on
  // top of what the child shares with the parent.
  const std::uint64_t memory = limits.memory_bytes > 0 ? limits.memory_bytes : physical_memory_bytes();
  if (memory > 0) {
    std::uint64_t data_kib = 0;
    if (FILE* f = std::fopen("/proc/self/status", "r")) {
      char line[256];
      while (std::fgets(line, sizeof line, f) != nullptr)
        if (std::sscanf(line, "VmData: %" SCNu64, &data_kib) == 1) break;
      std::fclose(f);
    }
    rlimit limit{};
    if (::getrlimit(RLIMIT_DATA, &limit) == 0) {
      const rlim_t want = static_cast<rlim_t>(data_kib * 1024 + memory);
      if (limit.rlim_max == RLIM_INFINITY || want < limit.rlim_max) {
        limit.rlim_cur = want;
        ::setrlimit(RLIMIT_DATA, &limit);
      }
    }
  }
  std::string out;
  char status = '+';
  try {
    out = work();
  } catch (const std::bad_alloc&) {
    status = '!';
    out = what + " asks for more than the " + std::to_string(memory >> 20) +
          " MiB its input's size allows: a count in it is corrupt";
  } catch (const std::exception& e) {
    status = '!';
    out = e.what();
  } catch (...) {
    status = '!';
    out = "failed with an unknown exception";
  }
  const bool ok = write_all(fd, &status, 1) && write_all(fd, out.data(), out.size());
  ::close(fd);
  ::_exit(ok ? 0 : 3);
}

std::string signal_name(int s) {
  switch (s) {
    case SIGABRT: return "SIGABRT";
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL, perhaps the out-of-memory killer";
    case SIGXCPU: return "SIGXCPU, past its CPU time";
    default: return "signal " + std::to_string(s);
  }
}

}  // namespace

std::string fenced_call(const std::string& what, const std::function<std::string()>& work, FenceLimits limits) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(what + ": cannot make a pipe for a fenced reader: " + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(what + ": cannot start a fenced reader process: " + std::strerror(e));
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(what, fds[1], work, limits);
  }
  ::close(fds[1]);
  std::string got;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)
    throw DataError(what + " used more than " + std::to_string(limits.cpu_seconds) +
                    " s of CPU time on it and was stopped: the file is corrupt or far larger than it looks");
  if (WIFSIGNALED(status))
    throw DataError(what + " crashed on it (" + signal_name(WTERMSIG(status)) +
                    "): the file is corrupt or not what it claims to be");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || got.empty())
    throw DataError(what + " ended without a result (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  if (got[0] == '!') throw DataError(got.substr(1));
  return got.substr(1);
}

}  // namespace habuffer
