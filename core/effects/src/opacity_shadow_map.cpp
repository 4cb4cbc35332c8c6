#include "habuffer/opacity_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace habuffer {

OpacityShadowMap::OpacityShadowMap(Extent size, std::uint32_t slices) : size_(size), slices_(slices) {
  if (size.area() == 0) throw std::invalid_argument("opacity shadow map: size " + size.str() + " has no pixels");
  if (slices == 0 || slices > 4096)
    throw std::invalid_argument("opacity shadow map: " + std::to_string(slices) + " slices is outside 1..4096");
  if (size.area() * (std::uint64_t{slices} + 1) > (std::uint64_t{1} << 32))
    throw std::invalid_argument("opacity shadow map: " + size.str() + " pixels of " + std::to_string(slices) +
                                " slices exceeds 2^32 planes");
  planes_.assign(size.area() * (std::size_t{slices} + 1), 1.0f);
}

void OpacityShadowMap::insert(std::span<const Fragment> fragments) {
  const std::size_t stride = std::size_t{slices_} + 1;
  for (const Fragment& f : fragments) {
    if (f.x >= size_.x || f.y >= size_.y)
      throw std::out_of_range("opacity shadow map: fragment at (" + std::to_string(f.x) + ", " + std::to_string(f.y) +
                              ") is off the map " + size_.str());
    if (!(f.depth >= 0.0f && f.depth <= 1.0f))
      throw std::invalid_argument("opacity shadow map: fragment depth " + std::to_string(f.depth) +
                                  " is outside [0, 1]");
    const float keep = 1.0f - static_cast<float>(f.rgba & 0xFFu) / 255.0f;
    // Every plane behind the fragment (k / N > t) sees it.
    const auto first = static_cast<std::uint32_t>(std::floor(f.depth * static_cast<float>(slices_))) + 1;
    float* pixel = planes_.data() + (f.x + std::size_t{f.y} * size_.x) * stride;
    for (std::uint32_t k = first; k <= slices_; ++k) pixel[k] *= keep;
  }
}

float OpacityShadowMap::transmittance(std::uint32_t x, std::uint32_t y, float t) const {
  if (x >= size_.x || y >= size_.y)
    throw std::out_of_range("opacity shadow map: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is off the map " + size_.str());
  const float s = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(slices_);
  const auto k = std::min(static_cast<std::uint32_t>(s), slices_ - 1);
  const float frac = s - static_cast<float>(k);
  const float* pixel = planes_.data() + (x + std::size_t{y} * size_.x) * (std::size_t{slices_} + 1);
  return pixel[k] + (pixel[k + 1] - pixel[k]) * frac;
}

}  // namespace habuffer
