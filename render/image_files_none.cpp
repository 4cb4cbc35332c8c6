// The image files of habuffer::render in a build without OpenImageIO
// (HABUFFER_WITH_IMAGES=OFF, for machines that cannot carry its libraries,
// such as a lent GPU machine): every file operation refuses with one error
// naming the file, so `habuffer render --stats` still runs and `--out`
// fails before any work (the CLI checks its outputs up front).
#include "habuffer/render/heatmap.h"
#include "habuffer/render/image.h"

namespace habuffer {
namespace {

[[noreturn]] void no_images(const std::string& what, const std::string& path) {
  throw ImageError("cannot " + what + " image '" + path +
                   "': this habuffer was built without image support (HABUFFER_WITH_IMAGES=OFF)");
}

}  // namespace

std::string image_support() { return "none (built with HABUFFER_WITH_IMAGES=OFF)"; }
bool has_image_support() { return false; }

void check_image_extension(const std::string&) {}  // every write refuses, naming the build

void write_image(const std::string& path, const Image&) { no_images("write", path); }

Image read_image(const std::string& path) { no_images("read", path); }

ImageDifference compare_images(const std::string& a, const std::string&) { no_images("compare", a); }

HeatmapRange write_heatmap(const std::string& path, Extent, std::span<const float>, const std::string&,
                           const std::string&) {
  no_images("write heat map", path);
}

}  // namespace habuffer
