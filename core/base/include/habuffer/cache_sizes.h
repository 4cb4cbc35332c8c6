/// @file
/// The data caches of the machine the library runs on, queried once: the CPU
/// path's latency hiding turns on where a table no longer fits the L2
/// (issue 36), and `habuffer info` reports what it found and where from.
#pragma once

#include <cstdint>
#include <string>

namespace habuffer {

/// Sizes in bytes of one core's view of the data caches (0: unknown).
struct CacheSizes {
  std::uint64_t l1d = 0;  ///< level-1 data cache of one core
  std::uint64_t l2 = 0;   ///< level-2 cache of one core (a shared L2 counts whole)
  std::uint64_t l3 = 0;   ///< last-level cache
  /// Where the sizes came from: "sysfs" (/sys/devices/system/cpu/cpu0/cache),
  /// "sysconf", or "default" (neither said: kDefaultL2Bytes assumed for the L2).
  std::string source;
};

/// The L2 assumed when the system says nothing: 1 MiB, a common size per
/// core on the x86-64 and Arm servers this library targets.
inline constexpr std::uint64_t kDefaultL2Bytes = std::uint64_t{1} << 20;

/// This machine's caches, queried on the first call (thread-safe). The L2 is
/// never 0 (kDefaultL2Bytes where unknown).
const CacheSizes& cache_sizes();

/// Parses a sysfs cache size ("512K", "32768K", "2M", "1048576"): bytes, or
/// 0 for text that is not a size. Exposed for the tests.
std::uint64_t parse_cache_size(const std::string& text);

}  // namespace habuffer
