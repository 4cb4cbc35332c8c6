#include "habuffer/memory_budget.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace habuffer {

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

void check_fits_in_memory(const std::string& what, std::uint64_t bytes) {
  const std::uint64_t available = physical_memory_bytes();
  if (available == 0 || bytes <= available) return;
  const auto gib = [](std::uint64_t b) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", static_cast<double>(b) / double(1u << 30));
    return std::string(text);
  };
  throw std::invalid_argument(what + " needs " + (bytes == UINT64_MAX ? std::string("more than 2^64 bytes") : gib(bytes) + " GiB") +
                              ", more than this machine's " + gib(available) + " GiB of memory");
}

}  // namespace habuffer
