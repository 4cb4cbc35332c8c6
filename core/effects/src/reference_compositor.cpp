#include "habuffer/reference_compositor.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/record_layout.h"

namespace habuffer {

namespace {

// Whether a fragment covers sample s of a screen of `samples` samples per
// pixel (written apart from the record code it checks): every fragment at one
// sample per pixel, a coverage word of 0 every sample, else its bit s.
bool covers(const Fragment& f, std::uint32_t samples, std::uint32_t s) {
  return samples == 1 || f.coverage == 0 || ((f.coverage >> s) & 1u) != 0;
}

template <class Background>
std::vector<glm::dvec4> composite_sorted(std::span<const Fragment> fragments, Extent screen, Background background,
                                         std::uint32_t samples) {
  if (!RecordLayout::samples_valid(samples))
    throw std::invalid_argument("reference_composite: samples " + std::to_string(samples) + " is not 1, 2, 4 or 8");
  // Counting sort by pixel, then a full sort within each pixel.
  std::vector<std::uint64_t> begin(screen.area() + 1, 0);
  for (const Fragment& f : fragments) {
    if (f.x >= screen.x || f.y >= screen.y) throw std::out_of_range("fragment outside screen " + screen.str());
    if (RecordLayout::depth_valid(f.depth)) ++begin[f.x + std::uint64_t{f.y} * screen.x + 1];
  }
  for (std::size_t i = 1; i < begin.size(); ++i) begin[i] += begin[i - 1];
  std::vector<Fragment> sorted(begin.back());
  std::vector<std::uint64_t> next(begin.begin(), begin.end() - 1);
  for (const Fragment& f : fragments)
    if (RecordLayout::depth_valid(f.depth)) sorted[next[f.x + std::uint64_t{f.y} * screen.x]++] = f;

  std::vector<glm::dvec4> image(screen.area());
  for (std::uint64_t p = 0; p < screen.area(); ++p) {
    auto first = sorted.begin() + static_cast<std::ptrdiff_t>(begin[p]);
    auto last = sorted.begin() + static_cast<std::ptrdiff_t>(begin[p + 1]);
    std::sort(first, last, [](const Fragment& a, const Fragment& b) {
      return a.depth < b.depth || (a.depth == b.depth && a.rgba > b.rgba);
    });
    // Each sample composites the fragments that cover it; the pixel is their mean.
    glm::dvec4 sum(0.0);
    for (std::uint32_t s = 0; s < samples; ++s) {
      glm::dvec4 c(0.0);
      for (auto it = first; it != last; ++it) {
        if (!covers(*it, samples, s)) continue;
        const std::uint32_t d = it->rgba;
        const glm::dvec3 rgb(d >> 24, (d >> 16) & 255u, (d >> 8) & 255u);
        const double a = (d & 255u) / 255.0;
        const double w = (1.0 - c.a) * a;
        c = glm::dvec4(glm::dvec3(c) + w * (rgb / 255.0), c.a + w);
      }
      sum += glm::dvec4(glm::dvec3(c) + (1.0 - c.a) * background(p), c.a);
    }
    image[p] = sum / static_cast<double>(samples);
  }
  return image;
}

}  // namespace

std::vector<glm::dvec4> reference_composite(std::span<const Fragment> fragments, Extent screen,
                                            glm::dvec3 background, std::uint32_t samples) {
  return composite_sorted(fragments, screen, [&](std::uint64_t) { return background; }, samples);
}

std::vector<glm::dvec4> reference_composite(std::span<const Fragment> fragments, Extent screen,
                                            std::span<const glm::vec3> backgrounds, std::uint32_t samples) {
  if (backgrounds.size() != screen.area())
    throw std::invalid_argument("reference_composite: " + std::to_string(backgrounds.size()) +
                                " backgrounds for screen " + screen.str());
  return composite_sorted(fragments, screen, [&](std::uint64_t p) { return glm::dvec3(backgrounds[p]); }, samples);
}

}  // namespace habuffer
