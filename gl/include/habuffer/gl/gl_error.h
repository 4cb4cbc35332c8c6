/// @file
/// Errors of the GPU path: a missing context or capability, a shader that does
/// not compile (with its log), or a GL error reported through KHR_debug.
#pragma once

#include <stdexcept>

namespace habuffer::gl {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace habuffer::gl
