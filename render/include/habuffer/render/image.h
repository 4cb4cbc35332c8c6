/// @file
/// Images in and out of `habuffer render` and `habuffer compare`, all through
/// OpenImageIO: PNG (8-bit) by default, EXR, HDR or TIFF (float) by the
/// file's extension; plus the exact reference image and the comparisons the
/// tests and reports measure techniques by.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <span>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"

namespace habuffer {

/// An image file could not be read, written or compared (the message names the file and the reason).
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;  ///< takes the message
};

/// RGBA in [0, 1], row-major with row 0 at the bottom (OpenGL's order).
struct Image {
  Extent size;                    ///< width and height in pixels
  std::vector<glm::vec4> pixels;  ///< size.area() pixels, row 0 at the bottom
};

/// "OpenImageIO 2.4.7.1", or "none (...)" in a build without image files
/// (HABUFFER_WITH_IMAGES=OFF), where the file functions below and
/// write_heatmap throw ImageError naming the file.
std::string image_support();
/// Whether this build reads and writes image files (false: HABUFFER_WITH_IMAGES=OFF).
bool has_image_support();

/// Throws std::invalid_argument naming the file, its extension and formats
/// that can be written unless OpenImageIO has a writer for the extension of
/// `path` ("x.txt" is refused before any work; no extension is PNG, as a
/// device such as /dev/stdout is written). A build without image files
/// accepts any name (its writers refuse every file). The writers below check it too.
void check_image_extension(const std::string& path);
/// Writes RGB (the image is already composited over its background), top row
/// first, in the format of the file's extension (PNG without one). Throws
/// ImageError naming the file and the reason (an extension no writer takes,
/// a full device: "No space left on device").
void write_image(const std::string& path, const Image& image);
/// Reads RGB(A) as floats, row 0 at the bottom; alpha 1 when the file has none, a one-channel file's
/// value in R, G and B. Throws ImageError naming the file.
Image read_image(const std::string& path);

/// The exact reference of `fragments` (SPEC 7 in double precision, each pixel
/// over its own background: `backgrounds` per pixel, row 0 at the bottom), as
/// a float image; `samples` above 1: per sample, averaged (reference_composite).
Image reference_image(std::span<const Fragment> fragments, Extent size, std::span<const glm::vec3> backgrounds,
                      std::uint32_t samples = 1);

/// How two images' RGB differ (compare_pixels, compare_images).
struct ImageDifference {
  double rmse = 0.0, psnr = 0.0, max_error = 0.0;  ///< over RGB, values in [0, 1]; psnr in dB
  int max_x = 0, max_y = 0, max_channel = 0;       ///< where the largest error is (top row 0)
};

/// The float images' RGB compared in memory (no 8-bit quantization): rmse,
/// psnr = 20 log10(1 / rmse) (infinite when identical), the largest absolute
/// error and where (top row 0). Throws ImageError when the sizes differ.
ImageDifference compare_pixels(const Image& image, const Image& reference);

/// OpenImageIO's comparison of the RGB channels. Throws ImageError when a file
/// cannot be read or the sizes differ (both sizes named).
ImageDifference compare_images(const std::string& a, const std::string& b);

}  // namespace habuffer
