#include "habuffer/parallel.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <string>
#include <stdexcept>
#include <thread>
#include <vector>

#if HABUFFER_WITH_TBB
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>
#endif

namespace habuffer {

#if HABUFFER_WITH_TBB

// ThreadSanitizer builds use the std::thread runtime below (CMakeLists.txt
// refuses HABUFFER_SANITIZE=thread with oneTBB, which is not instrumented).
void fork_join(std::uint32_t n, const std::function<void(std::uint32_t)>& body) {
  tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t i) { body(i); }, tbb::static_partitioner());
}

void run_with_threads(std::uint32_t threads, const std::function<void()>& work) {
  tbb::task_arena arena(static_cast<int>(threads));
  arena.execute(work);
}

std::uint32_t default_concurrency() { return static_cast<std::uint32_t>(tbb::info::default_concurrency()); }

std::string parallel_runtime() {
  return "oneTBB " + std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR);
}

#else

// One std::thread per index beyond the first, which runs on the caller.
void fork_join(std::uint32_t n, const std::function<void(std::uint32_t)>& body) {
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto run = [&](std::uint32_t i) {
    try {
      body(i);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(n > 0 ? n - 1 : 0);
  for (std::uint32_t i = 1; i < n; ++i) threads.emplace_back(run, i);
  if (n > 0) run(0);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

void run_with_threads(std::uint32_t, const std::function<void()>& work) { work(); }

std::uint32_t default_concurrency() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? n : 1;
}

std::string parallel_runtime() { return "std::thread"; }

#endif

std::uint32_t resolve_threads(std::uint32_t threads) {
  if (threads > kMaxThreads)
    throw std::invalid_argument(std::to_string(threads) + " threads: at most " + std::to_string(kMaxThreads));
  return threads != 0 ? threads : default_concurrency();
}

std::uint32_t resolve_threads(std::uint32_t threads, std::uint64_t work) {
  const std::uint32_t all = resolve_threads(threads);
  if (threads != 0) return all;
  return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(work / kWorkPerThread, 1, all));
}

}  // namespace habuffer
