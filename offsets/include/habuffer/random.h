/// @file
/// A small, fully specified PRNG (SplitMix64) so that offsets and generated
/// streams are identical on every platform and standard library.
#pragma once

#include <cstdint>

namespace habuffer {

__extension__ using Uint128 = unsigned __int128;  ///< GCC/Clang builtin, for Lemire's method

/// The SplitMix64 generator: 64 bits of state, the same stream for a seed everywhere.
class SplitMix64 {
 public:
  /// Starts from state `seed`.
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  /// The next 64-bit output.
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, bound), bound > 0, without modulo bias (Lemire 2019).
  std::uint64_t below(std::uint64_t bound) {
    Uint128 m = static_cast<Uint128>(next()) * bound;
    auto low = static_cast<std::uint64_t>(m);
    if (low < bound) {
      std::uint64_t threshold = (0 - bound) % bound;
      while (low < threshold) {
        m = static_cast<Uint128>(next()) * bound;
        low = static_cast<std::uint64_t>(m);
      }
    }
    return static_cast<std::uint64_t>(m >> 64);
  }

  /// Uniform float in [0, 1) with 24 random bits.
  float unit_float() { return static_cast<float>(next() >> 40) * 0x1.0p-24f; }

 private:
  std::uint64_t state_;
};

}  // namespace habuffer
