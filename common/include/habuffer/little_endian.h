/// @file
/// Fixed-width values appended to and read from a byte string, little-endian:
/// the binary files' fields (the voxel grid, the spatial hash's table).
#pragma once

#include <bit>
#include <cstddef>
#include <cstring>
#include <string>

namespace habuffer {

static_assert(std::endian::native == std::endian::little,
              "the binary files are little-endian: add byte swapping to put_le and take_le");

/// Appends v's bytes to `out`.
template <class T>
void put_le(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

/// The T at byte `at` of `in` (the caller checked the size).
template <class T>
T take_le(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

}  // namespace habuffer
