/// @file
/// An RGBA32F texture and framebuffer the GPU path resolves into, read back
/// as an Image: float, so the comparison with the reference sees no 8-bit
/// quantization.
#pragma once

#include <epoxy/gl.h>

#include <vector>

#include "habuffer/render/image.h"

namespace habuffer {

/// Owns one RGBA32F texture of `size` and a framebuffer with it as colour attachment 0; needs a current
/// context for its whole life.
class ResolveTarget {
 public:
  /// Creates the texture and framebuffer (contents undefined until drawn).
  explicit ResolveTarget(Extent size) : size_(size) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA32F, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y));
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
  }
  /// Deletes the framebuffer and texture.
  ~ResolveTarget() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }
  ResolveTarget(const ResolveTarget&) = delete;
  ResolveTarget& operator=(const ResolveTarget&) = delete;

  /// The framebuffer's GL name, to draw the resolve into.
  [[nodiscard]] unsigned framebuffer() const { return framebuffer_; }
  /// The texture read back, row 0 at the bottom.
  [[nodiscard]] Image read() const {
    Image image{size_, std::vector<glm::vec4>(size_.area())};
    glGetTextureImage(texture_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                      image.pixels.data());
    return image;
  }

 private:
  Extent size_;
  unsigned texture_ = 0, framebuffer_ = 0;
};

}  // namespace habuffer
