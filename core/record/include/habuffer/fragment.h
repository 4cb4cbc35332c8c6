/// @file
/// Fragments (SPEC 1), and (counters.h) the counters of SPEC invariant 1 for every technique.
#pragma once

#include <cstdint>

#include "habuffer/counters.h"

namespace habuffer {

/// One rasterized fragment: pixel, normalized depth t (0 = nearest), 32 bits
/// of data (R<<24 | G<<16 | B<<8 | A, straight alpha, for colour) and, on a
/// multisampled screen, the samples it covers.
struct Fragment {
  std::uint32_t x = 0;  ///< pixel column
  std::uint32_t y = 0;  ///< pixel row
  float depth = 0.0f;  ///< normalized depth t in [0, 1]; NaN or outside: invalid
  std::uint32_t rgba = 0;  ///< the 32-bit data word
  /// Bit s: the fragment covers sample s of its pixel (gl_SampleMaskIn[0]);
  /// 0: the whole pixel (no mask given). Read only when the buffer has more
  /// than one sample per pixel (BufferConfig::samples), where a mask with no
  /// bit among the S samples makes the fragment invalid.
  std::uint32_t coverage = 0;
  /// Memberwise equality.
  friend bool operator==(const Fragment&, const Fragment&) = default;
};

}  // namespace habuffer
