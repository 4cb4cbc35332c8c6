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

}  // namespace habuffer
