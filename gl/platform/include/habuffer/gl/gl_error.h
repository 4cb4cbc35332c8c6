/// @file
/// Errors of the GPU path: a missing context or capability, a shader that does
/// not compile (with its log), or a GL error reported through KHR_debug.
#pragma once

#include <stdexcept>

namespace habuffer::gl {

/// The exception of the GPU path; what() says what failed (a shader's error
/// carries the driver's log).
class GlError : public std::runtime_error {
 public:
  /// Constructs from a message, as std::runtime_error does.
  using std::runtime_error::runtime_error;
};

}  // namespace habuffer::gl
