// The image files of habuffer::render through OpenImageIO (built when
// HABUFFER_WITH_IMAGES is on; image_files_none.cpp otherwise).
#include "habuffer/render/image.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "habuffer/atomic_file.h"
#include "habuffer/csv.h"
#include "habuffer/memory_budget.h"
#include "habuffer/printable.h"
#include "image_files.h"

namespace habuffer {

std::string image_support() { return "OpenImageIO " OIIO_VERSION_STRING; }
bool has_image_support() { return true; }

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool float_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
}

// Whether OpenImageIO has a writer for files named like `name` (by extension);
// a failed lookup's message is taken so it is not left pending.
bool has_writer(const std::string& name) {
  const bool found = OIIO::ImageOutput::create(name) != nullptr;
  if (!found) (void)OIIO::geterror();
  return found;
}

// The format an image named `path` is written in: its extension's, PNG
// without one (a device such as /dev/stdout or /dev/full, or a bare name).
std::string write_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext.empty() ? std::string("png") : ext.substr(1);
}

// Images are read whole by OpenImageIO, which may seek: only regular files
// (a device such as /dev/zero would be read forever). The header's size is
// checked against the machine before the pixels are allocated.
OIIO::ImageBuf read_buffer(const std::string& path, std::uint64_t copies) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ImageError("image '" + path + "' does not exist");
  if (std::filesystem::is_directory(path, ec)) throw ImageError("image '" + path + "' is a directory, not an image");
  if (!std::filesystem::is_regular_file(path, ec))
    throw ImageError("image '" + path + "' is not a regular file (a device or pipe; images are read from files)");
  OIIO::ImageBuf buf;
  if (!buf.init_spec(path, 0, 0)) throw ImageError("image '" + path + "' cannot be read: " + buf.geterror());
  const OIIO::ImageSpec& spec = buf.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
    throw ImageError("image '" + path + "' is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     "x" + std::to_string(spec.depth) + " with " + std::to_string(spec.nchannels) +
                     " channels: not a 2D image");
  // Floats per channel, and the copies the caller makes of them (read_image's RGBA).
  const std::uint64_t pixels = saturating_product(static_cast<std::uint64_t>(spec.width), static_cast<std::uint64_t>(spec.height));
  const std::uint64_t bytes = saturating_product(pixels, saturating_product(static_cast<std::uint64_t>(spec.nchannels) * 4, copies));
  try {
    check_fits_in_memory("image '" + path + "' (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             " pixels, " + std::to_string(spec.nchannels) + " channels)",
                         bytes);
  } catch (const std::invalid_argument& e) {
    throw ImageError(e.what());
  }
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
    throw ImageError("image '" + path + "' cannot be read: " + buf.geterror());
  return buf;
}

}  // namespace

void check_image_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext.empty() || has_writer("x" + ext)) return;
  std::string formats;
  for (const char* f : {"png", "exr", "tif", "hdr", "jpg", "bmp", "tga", "webp"})
    if (has_writer(std::string("x.") + f)) formats += (formats.empty() ? "" : ", ") + std::string(f);
  throw std::invalid_argument(excerpt(path) + ": " + excerpt(ext) + " is not an image format OpenImageIO can write (" +
                              formats + ", ...)");
}

// OpenImageIO's writers can ignore a failed write (a PNG cut short by a
// full disk still reports success): the staged file is read back whole
// before it takes the output's name. A file-size limit is AtomicFile's
// check, for every output written by name.
void check_written_whole(const std::string& path, const std::string& staged, const OIIO::ImageSpec& spec) {
  const auto fail = [&](const std::string& why) {
    throw ImageError("image '" + path + "' cannot be written: " + why +
                     "; a full disk or a file-size limit stops a write midway");
  };
  // ImageInput, not ImageBuf: nothing of the staged name stays in the image cache.
  std::string why;
  if (auto in = OIIO::ImageInput::open(staged)) {
    const OIIO::ImageSpec& got = in->spec();
    std::vector<float> pixels(static_cast<std::size_t>(got.width) * static_cast<std::size_t>(got.height) *
                              static_cast<std::size_t>(std::max(got.nchannels, 1)));
    if (got.width == spec.width && got.height == spec.height &&
        in->read_image(0, 0, 0, got.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
      return;
    why = in->geterror();
  } else {
    why = OIIO::geterror();
  }
  fail(why.empty() ? std::string("what was written does not read back whole") : printable(why));
}

void write_atomically(const std::string& path, const OIIO::ImageBuf& buf) {
  try {
    check_image_extension(path);
  } catch (const std::invalid_argument& e) {
    throw ImageError(std::string("image ") + e.what());
  }
  std::error_code ec;
  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) std::filesystem::create_directories(dir, ec);
  try {
    AtomicFile out(path, AtomicFile::Access::ByName);
    errno = 0;
    if (!buf.write(out.staging_path(), OIIO::TypeUnknown, write_format(path))) {
      const int error = errno;
      std::string why = buf.geterror();
      if (why.empty()) why = OIIO::geterror();
      if (why.empty() && error != 0) why = std::strerror(error);
      if (why.empty()) why = "OpenImageIO could not write " + write_format(path) + " to " + printable(out.staging_path());
      throw ImageError("image '" + path + "' cannot be written: " + why);
    }
    out.check_staged_size();  // before the read-back: a cut PNG is a file-size limit's
    check_written_whole(path, out.staging_path(), buf.spec());
    out.commit();
  } catch (const DataError& e) {
    throw ImageError(std::string("image ") + e.what());
  }
}

void write_image(const std::string& path, const Image& image) {
  const Extent s = image.size;
  if (image.pixels.size() != s.area()) throw ImageError("image for '" + path + "' has the wrong number of pixels");
  if (s.x > static_cast<std::uint32_t>(INT32_MAX) || s.y > static_cast<std::uint32_t>(INT32_MAX))
    throw ImageError("image '" + path + "' of " + s.str() + " pixels: a side above 2^31 - 1, more than image files hold");
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
  const OIIO::ImageBuf buf = read_buffer(path, 3);  // the buffer, its copy, the RGBA image
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
  const OIIO::ImageBuf A = read_buffer(a, 1), B = read_buffer(b, 1);
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
