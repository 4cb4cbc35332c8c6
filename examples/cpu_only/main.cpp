// habuffer on the CPU alone: fragments in any order, an HA-buffer that keeps
// every pixel's list sorted front to back as it is built, a lossless build
// that reports (never hides) anything dropped, and the composited image.
//
// Exits 0 when the composited pixel equals the front-to-back blend computed
// by hand here, 1 otherwise.
#include <cmath>
#include <cstdio>
#include <vector>

#include <habuffer/habuffer.h>

namespace {

// Straight-alpha colour in the library's packing: R<<24 | G<<16 | B<<8 | A.
std::uint32_t rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
  return r << 24 | g << 16 | b << 8 | a;
}

}  // namespace

int main() {
  const habuffer::Extent screen{64, 48};
  // Three fragments on pixel (10, 20), arriving back to front, plus a
  // screenful of fragments elsewhere at depth 0.5.
  std::vector<habuffer::Fragment> fragments{{10, 20, 0.75f, rgba(0, 0, 255, 128)},
                                            {10, 20, 0.50f, rgba(0, 255, 0, 128)},
                                            {10, 20, 0.25f, rgba(255, 0, 0, 128)}};
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      if (x != 10 || y != 20) fragments.push_back({x, y, 0.5f, rgba(255, 255, 255, 64)});

  habuffer::BufferConfig config;
  config.screen = screen;
  config.table = {72, 54};  // load 0.8 of the fragments
  habuffer::ResizePolicy policy;
  // Lossless mode: up to 4 attempts, the table grown after any failure.
  const habuffer::BuildResult result = habuffer::build(config, habuffer::OffsetSource{}, fragments, {}, policy, 4);
  const habuffer::Counters& c = result.counters;
  std::printf("fragments %llu, stored %llu, failed %llu, attempts %zu, table %s\n",
              static_cast<unsigned long long>(c.fragments), static_cast<unsigned long long>(c.stored()),
              static_cast<unsigned long long>(c.failures()), result.attempts.size(),
              result.buffer.table().str().c_str());
  if (!result.lossless()) {
    std::fprintf(stderr, "cpu_only: %llu fragments could not be stored\n",
                 static_cast<unsigned long long>(c.failures()));
    return 1;
  }

  std::vector<habuffer::ListEntry> list;
  result.buffer.list(10, 20, list);
  std::printf("pixel (10, 20): %zu entries, nearest first:", list.size());
  for (const habuffer::ListEntry& e : list) std::printf(" %08x", e.data);
  std::printf("\n");

  // Front to back: red (a 128/255), green, blue, over a black background.
  const float a = 128.0f / 255.0f;
  const float expected[3] = {a, (1 - a) * a, (1 - a) * (1 - a) * a};
  const glm::vec4 got = result.buffer.composite(10, 20, glm::vec3(0.0f));
  std::printf("composited: %.6f %.6f %.6f alpha %.6f\n", got.r, got.g, got.b, got.a);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(got[k] - expected[k]) > 1e-6f) {
      std::fprintf(stderr, "cpu_only: channel %d is %.6f, expected %.6f\n", k, got[k], expected[k]);
      return 1;
    }
  return list.size() == 3 ? 0 : 1;
}
