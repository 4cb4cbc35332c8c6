// SPEC 7: traversal order and compositing, float32 against the double reference.
#include <gtest/gtest.h>

#include "habuffer/reference_compositor.h"
#include "test_support.h"

namespace habuffer {
namespace {

TEST(Compositing, EmptyPixelShowsTheBackground) {
  HaBuffer b = test::make_buffer(test::config({2, 2}, {2, 2}));
  const glm::vec4 c = b.composite(1, 1, glm::vec3(0.25f, 0.5f, 1.0f));
  EXPECT_EQ(c, glm::vec4(0.25f, 0.5f, 1.0f, 0.0f));
}

TEST(Compositing, OpaqueFrontHidesEverythingAndTransparentFragmentsVanish) {
  HaBuffer b = test::make_buffer(test::config({2, 2}, {4, 4}));
  b.insert(std::vector<Fragment>{{0, 0, 0.6f, 0x00FF00FFu},   // opaque green behind
                                 {0, 0, 0.3f, 0xFF000000u},   // red with alpha 0 in front
                                 {0, 0, 0.1f, 0x0000FFFFu},   // opaque blue in front of all
                                 {1, 0, 0.5f, 0xFF000000u}});  // only a transparent fragment
  EXPECT_EQ(b.composite(0, 0, glm::vec3(1.0f)), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  EXPECT_EQ(b.composite(1, 0, glm::vec3(0.5f)), glm::vec4(0.5f, 0.5f, 0.5f, 0.0f));
}

TEST(Compositing, FrontToBackUnderOperatorMatchesTheFormula) {
  HaBuffer b = test::make_buffer(test::config({1, 1}, {4, 4}));
  b.insert(std::vector<Fragment>{{0, 0, 0.7f, 0x0000FF80u}, {0, 0, 0.2f, 0xFF000040u}});
  const float a1 = 64.0f / 255.0f, a2 = 128.0f / 255.0f;
  const float r = a1 * 1.0f;
  const float ca = a1;
  const float w2 = (1.0f - ca) * a2;
  const glm::vec4 expected(r + (1.0f - (ca + w2)) * 0.0f, 0.0f, w2 * 1.0f, ca + w2);
  const glm::vec4 got = b.composite(0, 0, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(got.r, expected.r);
  EXPECT_FLOAT_EQ(got.b, expected.b);
  EXPECT_FLOAT_EQ(got.a, expected.a);
}

// Many layers: float32 compositing stays within 1e-4 of the double reference
// (depths on a 2^-20 grid and no duplicates, so both sort identically).
TEST(Compositing, Float32AgreesWithDoubleReferenceOverDeepLists) {
  const Extent screen{16, 16};
  SplitMix64 rng(3);
  std::vector<Fragment> f;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x)
      for (int k = 0; k < 40; ++k)
        f.push_back({x, y, static_cast<float>(rng.below(1u << 20)) * 0x1.0p-20f,
                     static_cast<std::uint32_t>(rng.next() & 0xFFFFFF00u) | static_cast<std::uint32_t>(1 + rng.below(40))});
  BufferConfig c = test::config(screen, {128, 128});  // load 0.63
  HaBuffer b = test::make_buffer(c);
  ASSERT_EQ(b.insert(f).failures(), 0u);
  const auto ref = reference_composite(f, screen, glm::dvec3(0.1, 0.2, 0.3));
  const auto img = b.composite_image(glm::vec3(0.1f, 0.2f, 0.3f), 2);
  for (std::size_t i = 0; i < img.size(); ++i)
    for (int ch = 0; ch < 4; ++ch) ASSERT_NEAR(img[i][ch], ref[i][ch], 1e-4) << "pixel " << i << " channel " << ch;
}

// The CPU composites a row's pixels as a wavefront, kWavefrontPixels of them
// age by age (techniques/ha/cpu/src/wavefront_composite.h): each pixel must still blend its own
// records in its own order, so every pixel equals the one-pixel walk of
// shared/ha_traverse.glsl bit for bit: widths that are no multiple of the
// wavefront, tables that wrap, pixels whose walks stop at different ages,
// empty pixels beside deep ones, per-pixel backgrounds, any thread count.
TEST(Compositing, TheWavefrontImageEqualsEachPixelsOwnWalkBitForBit) {
  struct Case {
    Extent screen, table;
    StreamKind kind;
    double load;
  };
  for (const Case& c : {Case{{13, 9}, {13, 9}, StreamKind::Coherent, 0.9}, Case{{37, 21}, {50, 29}, StreamKind::Random, 0.7},
                        Case{{1, 17}, {2, 17}, StreamKind::Random, 0.8}, Case{{64, 40}, {64, 40}, StreamKind::Coherent, 0.95}})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE("screen " + c.screen.str() + " table " + c.table.str() + " seed " + std::to_string(seed));
      HaBuffer b = test::make_buffer(test::config(c.screen, c.table), seed);
      const auto n = static_cast<std::uint64_t>(c.load * static_cast<double>(c.table.area()));
      b.insert(test::stream(c.screen, c.kind, n, seed));
      std::vector<glm::vec3> backgrounds(c.screen.area());
      for (std::size_t i = 0; i < backgrounds.size(); ++i)
        backgrounds[i] = glm::vec3(static_cast<float>(i % 7) / 7.0f, 0.25f, static_cast<float>(i % 3) / 3.0f);
      std::vector<glm::vec4> walked(c.screen.area()), walked_uniform(c.screen.area());
      for (std::uint32_t y = 0; y < c.screen.y; ++y)
        for (std::uint32_t x = 0; x < c.screen.x; ++x) {
          const std::size_t i = x + std::size_t{y} * c.screen.x;
          walked[i] = b.composite(x, y, backgrounds[i]);
          walked_uniform[i] = b.composite(x, y, glm::vec3(0.5f));
        }
      for (std::uint32_t threads : {1u, 3u}) {
        EXPECT_TRUE(test::same_bits(b.composite_image(backgrounds, threads), walked));
        EXPECT_TRUE(test::same_bits(b.composite_image(glm::vec3(0.5f), threads), walked_uniform));
      }
    }
}

TEST(Compositing, ReferenceSortsByUnquantizedDepthThenLargerDataFirst) {
  const std::vector<Fragment> f{{0, 0, 0.5f, 0x00FF00FFu}, {0, 0, 0.5f, 0xFF0000FFu}, {0, 0, 0.1f, 0x00000000u}};
  const auto ref = reference_composite(f, {1, 1}, glm::dvec3(0.0));
  EXPECT_DOUBLE_EQ(ref[0].r, 1.0) << "equal depth: larger data (red) in front";
  EXPECT_DOUBLE_EQ(ref[0].g, 0.0);
}

}  // namespace
}  // namespace habuffer
