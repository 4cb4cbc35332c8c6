#include "habuffer/cache_sizes.h"

#include <unistd.h>

#include <cctype>
#include <fstream>
#include <string>

namespace habuffer {
namespace {

std::string read_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  if (in) std::getline(in, line);
  return line;
}

// cpu0's caches from sysfs (Linux): index0..indexN, each a level, a type and a size.
CacheSizes from_sysfs() {
  CacheSizes c;
  for (int i = 0; i < 16; ++i) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i) + "/";
    const std::string level = read_line(dir + "level"), type = read_line(dir + "type");
    if (level.empty()) break;
    if (type == "Instruction") continue;
    const std::uint64_t size = parse_cache_size(read_line(dir + "size"));
    if (level == "1") c.l1d = size;
    else if (level == "2") c.l2 = size;
    else if (level == "3") c.l3 = size;
  }
  return c;
}

CacheSizes from_sysconf() {
  CacheSizes c;
  const auto query = [](int name) {
    const long v = ::sysconf(name);
    return v > 0 ? static_cast<std::uint64_t>(v) : std::uint64_t{0};
  };
#if defined(_SC_LEVEL2_CACHE_SIZE)
  c.l1d = query(_SC_LEVEL1_DCACHE_SIZE);
  c.l2 = query(_SC_LEVEL2_CACHE_SIZE);
  c.l3 = query(_SC_LEVEL3_CACHE_SIZE);
#else
  (void)query;
#endif
  return c;
}

CacheSizes query_caches() {
  CacheSizes c = from_sysfs();
  if (c.l2 != 0) {
    c.source = "sysfs";
    return c;
  }
  c = from_sysconf();
  if (c.l2 != 0) {
    c.source = "sysconf";
    return c;
  }
  c.l2 = kDefaultL2Bytes;
  c.source = "default";
  return c;
}

}  // namespace

std::uint64_t parse_cache_size(const std::string& text) {
  std::size_t i = 0;
  std::uint64_t v = 0;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
    if (v > (UINT64_MAX - 9) / 10) return 0;
    v = v * 10 + static_cast<std::uint64_t>(text[i] - '0');
  }
  if (i == 0) return 0;
  std::uint64_t scale = 1;
  if (i < text.size()) {
    switch (text[i]) {
      case 'K': case 'k': scale = std::uint64_t{1} << 10; break;
      case 'M': case 'm': scale = std::uint64_t{1} << 20; break;
      case 'G': case 'g': scale = std::uint64_t{1} << 30; break;
      default: return 0;
    }
    ++i;
  }
  if (i != text.size() || v > UINT64_MAX / scale) return 0;
  return v * scale;
}

const CacheSizes& cache_sizes() {
  static const CacheSizes sizes = query_caches();
  return sizes;
}

}  // namespace habuffer
