#include "habuffer/render/heatmap.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "habuffer/render/image.h"
#include "image_files.h"

namespace habuffer {
namespace {

constexpr int kLegendHeight = 40, kRampHeight = 12, kMargin = 6;

// One channel of `values` / top, top row first.
OIIO::ImageBuf normalized(Extent size, std::span<const float> values, double top) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(static_cast<int>(size.x), static_cast<int>(size.y), 1, OIIO::TypeDesc::FLOAT));
  std::vector<float> v(size.area());
  const double scale = top > 0.0 ? 1.0 / top : 0.0;
  for (std::uint32_t y = 0; y < size.y; ++y)
    for (std::uint32_t x = 0; x < size.x; ++x)
      v[x + std::size_t{y} * size.x] = static_cast<float>(values[x + std::size_t{size.y - 1 - y} * size.x] * scale);
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, v.data());
  return buf;
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);
  return s;
}

// The legend strip: the ramp from 0 to `top`, labelled when a font is found.
OIIO::ImageBuf legend(int width, double top, const std::string& title, const std::string& colour_map) {
  OIIO::ImageBuf ramp(OIIO::ImageSpec(std::max(width - 2 * kMargin, 1), kRampHeight, 1, OIIO::TypeDesc::FLOAT));
  for (int x = 0; x < ramp.spec().width; ++x)
    for (int y = 0; y < kRampHeight; ++y) {
      const float v = static_cast<float>(x) / static_cast<float>(std::max(ramp.spec().width - 1, 1));
      ramp.setpixel(x, y, &v);
    }
  OIIO::ImageBuf strip(OIIO::ImageSpec(width, kLegendHeight, 3, OIIO::TypeDesc::FLOAT));
  const float grey[3] = {0.12f, 0.12f, 0.12f};
  OIIO::ImageBufAlgo::fill(strip, grey);
  OIIO::ImageBufAlgo::paste(strip, kMargin, kMargin, 0, 0, OIIO::ImageBufAlgo::color_map(ramp, 0, colour_map));
  const float white[3] = {1.0f, 1.0f, 1.0f};
  const int baseline = kLegendHeight - 6;
  // Best effort: render_text fails without a font, and the ramp still says enough with the range in the stats.
  OIIO::ImageBufAlgo::render_text(strip, kMargin, baseline, "0", 13, "DejaVuSans", white);
  OIIO::ImageBufAlgo::render_text(strip, width / 2, baseline, title, 13, "DejaVuSans", white,
                                  OIIO::ImageBufAlgo::TextAlignX::Center);
  OIIO::ImageBufAlgo::render_text(strip, width - kMargin, baseline, number(top), 13, "DejaVuSans", white,
                                  OIIO::ImageBufAlgo::TextAlignX::Right);
  (void)strip.geterror();  // drop a missing-font message (the ramp still says enough)
  (void)OIIO::geterror();
  return strip;
}

}  // namespace

HeatmapRange write_heatmap(const std::string& path, Extent size, std::span<const float> values, const std::string& title,
                           const std::string& colour_map) {
  if (values.size() != size.area()) throw ImageError("heat map '" + path + "' has the wrong number of values");
  HeatmapRange range{0.0, 0.0};
  if (!values.empty()) {
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    range = {*lo, *hi};
  }
  const OIIO::ImageBuf coloured = OIIO::ImageBufAlgo::color_map(normalized(size, values, range.max), 0, colour_map);
  if (coloured.has_error()) throw ImageError("heat map '" + path + "': " + coloured.geterror());
  const int w = static_cast<int>(size.x), h = static_cast<int>(size.y);
  OIIO::ImageBuf out(OIIO::ImageSpec(w, h + kLegendHeight, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::paste(out, 0, 0, 0, 0, coloured);
  OIIO::ImageBufAlgo::paste(out, 0, h, 0, 0, legend(w, range.max, title, colour_map));
  out.set_write_format(OIIO::TypeDesc::UINT8);
  write_atomically(path, out);
  return range;
}

}  // namespace habuffer
