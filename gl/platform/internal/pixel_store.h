// The host's unpack state out of the way of one library call: OpenGL's
// buffer and texture clears (glClearNamedBufferData, glClearTexImage) read
// their clear value through the pixel-unpack parameters, and Mesa applies
// GL_UNPACK_SKIP_ROWS and GL_UNPACK_SKIP_PIXELS to it: a host's skips made a
// zeroed counter block read garbage (issue 35). The scope saves the unpack
// parameters and the pixel-unpack buffer binding, sets GL's initial values
// (no skips, rows tightly packed, alignment 4, no unpack buffer), and puts
// the host's back when it ends.
#pragma once

#include <array>

#include <epoxy/gl.h>

namespace habuffer::gl {

class NeutralUnpack {
 public:
  NeutralUnpack();
  ~NeutralUnpack();
  NeutralUnpack(const NeutralUnpack&) = delete;
  NeutralUnpack& operator=(const NeutralUnpack&) = delete;

 private:
  std::array<GLint, 8> unpack_ = {};  // the unpack parameters, in the order of kUnpackParameters
  GLint unpack_buffer_ = 0;
};

}  // namespace habuffer::gl
