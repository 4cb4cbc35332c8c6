/// @file
/// The heat maps habuffer-view draws over the scene (depth complexity,
/// early-culled fragments, max age): one value a pixel from a shader-storage
/// buffer, blended over whatever framebuffer is bound, in the viewport given.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/gl/shader_program.h"

namespace habuffer::view {

/// A rectangle of the window's framebuffer (pixels from the bottom left).
struct ViewRect {
  int x = 0, y = 0;
  Extent size;
};

class HeatOverlay {
 public:
  HeatOverlay();
  ~HeatOverlay();
  HeatOverlay(const HeatOverlay&) = delete;
  HeatOverlay& operator=(const HeatOverlay&) = delete;

  /// Word `first + stride * pixel` of `buffer` for each pixel of `screen`,
  /// coloured on a ramp that reaches red at `full`, over the bound
  /// framebuffer's `viewport` (where the scene image was drawn), at 60 %
  /// opacity; pixels of value 0 are left alone.
  void draw(unsigned buffer, std::uint32_t first, std::uint32_t stride, Extent screen, double full, ViewRect viewport);
  /// The same for values held on the CPU (uploaded into a buffer of its own).
  void draw(const std::vector<std::uint32_t>& values, Extent screen, double full, ViewRect viewport);

 private:
  gl::ShaderProgram program_;
  unsigned vertex_array_ = 0;
  unsigned upload_ = 0;
  std::uint64_t upload_words_ = 0;
};

}  // namespace habuffer::view
