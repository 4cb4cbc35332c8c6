#include "pixel_store.h"

namespace habuffer::gl {
namespace {

constexpr GLenum kUnpackParameters[8] = {GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST,   GL_UNPACK_ROW_LENGTH,
                                         GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS,
                                         GL_UNPACK_SKIP_IMAGES, GL_UNPACK_ALIGNMENT};

GLint initial_value(GLenum parameter) { return parameter == GL_UNPACK_ALIGNMENT ? 4 : 0; }

}  // namespace

NeutralUnpack::NeutralUnpack() {
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
  for (std::size_t i = 0; i < unpack_.size(); ++i) {
    glGetIntegerv(kUnpackParameters[i], &unpack_[i]);
    if (unpack_[i] != initial_value(kUnpackParameters[i]))
      glPixelStorei(kUnpackParameters[i], initial_value(kUnpackParameters[i]));
  }
  if (unpack_buffer_ != 0) glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

NeutralUnpack::~NeutralUnpack() {
  for (std::size_t i = 0; i < unpack_.size(); ++i)
    if (unpack_[i] != initial_value(kUnpackParameters[i])) glPixelStorei(kUnpackParameters[i], unpack_[i]);
  // A host buffer deleted meanwhile cannot be: the scope spans one library call.
  if (unpack_buffer_ != 0) glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(unpack_buffer_));
}

}  // namespace habuffer::gl
