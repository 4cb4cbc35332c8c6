/// @file
/// The library's error for data it cannot use: a bad input file (io's
/// readers), or a stream a lossless build could not hold
/// (habuffer/lossless_build.h, require_lossless). The CLI exits 1 on it; the
/// Python module raises habuffer.DataError.
#pragma once

#include <stdexcept>

namespace habuffer {

/// Bad data: an input file's, or a stream lossless mode could not hold (the CLI exits 1 on it).
class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;  ///< takes the message
};

}  // namespace habuffer
