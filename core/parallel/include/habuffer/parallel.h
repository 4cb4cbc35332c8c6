/// @file
/// Fork-join over indices 0..n-1, the only parallel primitive of the CPU
/// path. Built on oneTBB when the library was configured with it
/// (HABUFFER_WITH_TBB, the default), on std::thread otherwise; the header
/// names neither, so a host never needs oneTBB's headers.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace habuffer {

/// Calls body(i) for every i in [0, n), one task per index (static split),
/// and returns when all have finished. Inside run_with_threads the tasks
/// share that many threads. An exception thrown by a task is rethrown here.
void fork_join(std::uint32_t n, const std::function<void(std::uint32_t)>& body);

/// Runs `work` with at most `threads` threads available to the fork_joins
/// inside it (a oneTBB task arena; std::thread builds run `work` directly).
void run_with_threads(std::uint32_t threads, const std::function<void()>& work);

/// The threads the parallel runtime uses by default (hardware threads).
std::uint32_t default_concurrency();

/// The parallel runtime, for reports: "oneTBB 2021.8" or "std::thread".
std::string parallel_runtime();

/// Most threads any call takes (the CLI's --threads bound): far more than
/// any machine this library targets uses, and far below where oneTBB's
/// arenas fail (tens of thousands).
inline constexpr std::uint32_t kMaxThreads = 1024;
/// The threads `threads` means (0: every hardware thread). Throws
/// std::invalid_argument above kMaxThreads.
std::uint32_t resolve_threads(std::uint32_t threads);
/// Work items (fragments to insert, pixels to sort or composite) that pay
/// for one more thread of a default count: sorted lists and the k-buffer,
/// which make no pass over every pixel, gained from two threads at 48-64 K
/// fragments and lost below 32 K (docs/performance.md, "Issue 26: CPU
/// threads for every technique").
inline constexpr std::uint64_t kWorkPerThread = 32768;
/// The threads `threads` means for a call over `work` items: an explicit
/// count is honoured (throws std::invalid_argument above kMaxThreads); 0
/// means every hardware thread, but no more than one per kWorkPerThread
/// items and at least one, so the default never splits a small batch.
std::uint32_t resolve_threads(std::uint32_t threads, std::uint64_t work);

}  // namespace habuffer
