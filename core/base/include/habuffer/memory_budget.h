/// @file
/// Sizes checked against the machine before anything is allocated: a typo in
/// a size (100000x100000) is one clear error naming the option at once, not
/// "out of memory" after minutes of work.
#pragma once

#include <cstdint>
#include <string>

namespace habuffer {

/// Physical memory of this machine in bytes, or 0 when unknown.
std::uint64_t physical_memory_bytes();

/// Throws std::invalid_argument "WHAT needs N GiB, more than this machine's
/// M GiB of memory" when `bytes` exceeds the physical memory (nothing when
/// it is unknown). `what` names the option or input that asked for it.
void check_fits_in_memory(const std::string& what, std::uint64_t bytes);

/// a * b, or UINT64_MAX when the product overflows.
std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b);

}  // namespace habuffer
