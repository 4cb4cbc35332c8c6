#include "habuffer/render/image.h"

#include "habuffer/reference_compositor.h"

#include <cmath>
#include <limits>

namespace habuffer {

ImageDifference compare_pixels(const Image& image, const Image& reference) {
  if (image.size != reference.size || image.pixels.size() != reference.pixels.size())
    throw ImageError("images differ in size: " + image.size.str() + " and " + reference.size.str());
  ImageDifference d;
  double sum = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(static_cast<double>(image.pixels[i][c]) - static_cast<double>(reference.pixels[i][c]));
      sum += e * e;
      if (e > d.max_error) {
        d.max_error = e;
        d.max_x = static_cast<int>(i % image.size.x);
        d.max_y = static_cast<int>(image.size.y - 1 - i / image.size.x);
        d.max_channel = c;
      }
    }
  const double n = static_cast<double>(image.pixels.size()) * 3.0;
  d.rmse = n > 0 ? std::sqrt(sum / n) : 0.0;
  d.psnr = d.rmse > 0 ? 20.0 * std::log10(1.0 / d.rmse) : std::numeric_limits<double>::infinity();
  return d;
}

Image reference_image(std::span<const Fragment> fragments, Extent size, std::span<const glm::vec3> backgrounds,
                      std::uint32_t samples) {
  const std::vector<glm::dvec4> exact = reference_composite(fragments, size, backgrounds, samples);
  Image image{size, std::vector<glm::vec4>(exact.size())};
  for (std::size_t i = 0; i < exact.size(); ++i) image.pixels[i] = glm::vec4(exact[i]);
  return image;
}

}  // namespace habuffer
