// An RGBA32F texture and framebuffer the GPU path resolves into, read back
// as an Image.
#pragma once

#include <epoxy/gl.h>

#include <vector>

#include "habuffer/render/image.h"

namespace habuffer {

class ResolveTarget {
 public:
  explicit ResolveTarget(Extent size) : size_(size) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA32F, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y));
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
  }
  ~ResolveTarget() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }
  ResolveTarget(const ResolveTarget&) = delete;
  ResolveTarget& operator=(const ResolveTarget&) = delete;

  [[nodiscard]] unsigned framebuffer() const { return framebuffer_; }
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
