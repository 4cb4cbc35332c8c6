/// @file
/// Division and remainder of 32-bit values by a runtime constant without a
/// hardware divide (Lemire, Kaser and Kurz, "Faster remainder by direct
/// computation", 2019): exact for every 32-bit dividend and divisor >= 1.
#pragma once

#include <cstdint>

#include "habuffer/random.h"

namespace habuffer {

/// Division and remainder by a fixed 32-bit divisor d, d >= 1 (see above).
class FastDivisor {
 public:
  /// Divides by d, which must be at least 1.
  explicit FastDivisor(std::uint32_t d = 1) : magic_(~std::uint64_t{0} / d + 1), d_(d) {}

  /// For d = 1 the magic wraps to 0, which div() special-cases and mod() gets right.
  [[nodiscard]] std::uint32_t div(std::uint32_t v) const {
    if (magic_ == 0) return v;
    return static_cast<std::uint32_t>((static_cast<Uint128>(magic_) * v) >> 64);
  }
  /// v mod d.
  [[nodiscard]] std::uint32_t mod(std::uint32_t v) const {
    const std::uint64_t low = magic_ * v;
    return static_cast<std::uint32_t>((static_cast<Uint128>(low) * d_) >> 64);
  }
  /// The divisor d.
  [[nodiscard]] std::uint32_t divisor() const { return d_; }

 private:
  std::uint64_t magic_;
  std::uint32_t d_;
};

}  // namespace habuffer
