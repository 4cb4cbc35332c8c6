// The image files of habuffer::render through OpenImageIO (built when
// HABUFFER_WITH_IMAGES is on; image_files_none.cpp otherwise).
#include "habuffer/render/image.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "habuffer/atomic_file.h"
#include "habuffer/csv.h"
#include "image_files.h"

namespace habuffer {

std::string image_support() { return "OpenImageIO " OIIO_VERSION_STRING; }
bool has_image_support() { return true; }

namespace {

bool float_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
}

// Images are read whole by OpenImageIO, which may seek: only regular files
// (a device such as /dev/zero would be read forever).
OIIO::ImageBuf read_buffer(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ImageError("image '" + path + "' does not exist");
  if (!std::filesystem::is_regular_file(path, ec))
    throw ImageError("image '" + path + "' is not a regular file");
  OIIO::ImageBuf buf(path);
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
    throw ImageError("image '" + path + "' cannot be read: " + buf.geterror());
  return buf;
}

}  // namespace

void write_atomically(const std::string& path, const OIIO::ImageBuf& buf) {
  std::error_code ec;
  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) std::filesystem::create_directories(dir, ec);
  try {
    AtomicFile out(path, AtomicFile::Access::ByName);
    if (!buf.write(out.staging_path())) {
      std::string why = buf.geterror();
      if (why.empty()) why = "OpenImageIO gave no reason";
      throw ImageError("image '" + path + "' cannot be written: " + why);
    }
    out.commit();
  } catch (const DataError& e) {
    throw ImageError(std::string("image ") + e.what());
  }
}

void write_image(const std::string& path, const Image& image) {
  const Extent s = image.size;
  if (image.pixels.size() != s.area()) throw ImageError("image for '" + path + "' has the wrong number of pixels");
  OIIO::ImageBuf buf(OIIO::ImageSpec(static_cast<int>(s.x), static_cast<int>(s.y), 3, OIIO::TypeDesc::FLOAT));
  std::vector<float> rgb(s.area() * 3);
  for (std::uint32_t y = 0; y < s.y; ++y)
    for (std::uint32_t x = 0; x < s.x; ++x) {
      const glm::vec4& p = image.pixels[x + std::size_t{s.y - 1 - y} * s.x];  // top row first
      for (int c = 0; c < 3; ++c) rgb[(x + std::size_t{y} * s.x) * 3 + c] = std::clamp(p[c], 0.0f, 1.0f);
    }
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, rgb.data());
  buf.set_write_format(float_format(path) ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  write_atomically(path, buf);
}

Image read_image(const std::string& path) {
  const OIIO::ImageBuf buf = read_buffer(path);
  const OIIO::ImageSpec& spec = buf.spec();
  Image image;
  image.size = {static_cast<std::uint32_t>(spec.width), static_cast<std::uint32_t>(spec.height)};
  std::vector<float> all(image.size.area() * static_cast<std::size_t>(spec.nchannels));
  buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, all.data());
  image.pixels.resize(image.size.area());
  const auto n = static_cast<std::size_t>(spec.nchannels);
  for (std::uint32_t y = 0; y < image.size.y; ++y)
    for (std::uint32_t x = 0; x < image.size.x; ++x) {
      const float* p = &all[(x + std::size_t{y} * image.size.x) * n];
      glm::vec4 v(p[0], n > 1 ? p[1] : p[0], n > 2 ? p[2] : p[0], n > 3 ? p[3] : 1.0f);
      image.pixels[x + std::size_t{image.size.y - 1 - y} * image.size.x] = v;
    }
  return image;
}

ImageDifference compare_images(const std::string& a, const std::string& b) {
  const OIIO::ImageBuf A = read_buffer(a), B = read_buffer(b);
  if (A.spec().width != B.spec().width || A.spec().height != B.spec().height)
    throw ImageError("images differ in size: '" + a + "' is " + std::to_string(A.spec().width) + "x" +
                     std::to_string(A.spec().height) + ", '" + b + "' is " + std::to_string(B.spec().width) + "x" +
                     std::to_string(B.spec().height));
  OIIO::ROI rgb = A.roi();
  rgb.chbegin = 0;
  rgb.chend = std::min({3, A.spec().nchannels, B.spec().nchannels});
  const OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(A, B, 1.0f, 1.0f, rgb);
  if (r.error) throw ImageError("comparing '" + a + "' and '" + b + "' failed: " + OIIO::geterror());
  ImageDifference d;
  d.rmse = r.rms_error;
  d.psnr = r.PSNR;
  d.max_error = r.maxerror;
  d.max_x = r.maxx;
  d.max_y = r.maxy;
  d.max_channel = r.maxc;
  return d;
}

}  // namespace habuffer
