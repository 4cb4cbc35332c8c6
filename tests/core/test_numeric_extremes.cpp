// Numerical extremes users should expect, each stated in the test's name.
#include <gtest/gtest.h>

#include <cmath>

#include "habuffer/hash_kernel.h"
#include "habuffer/reference_compositor.h"
#include "test_support.h"

namespace habuffer {
namespace {

using Kernel = HashKernel<std::uint64_t, false>;

Kernel blend_only_kernel() { return Kernel(KernelParams{}, nullptr, nullptr, nullptr); }

// Float32 under-compositing of n layers of opacity a: the error obeys
// e' = (1 - a) e + d with |d| <= 3 * 2^-24 (three roundings per step), so it
// never exceeds 3 * 2^-24 / a, however many layers.
TEST(NumericExtremes, TenThousandLayersInFloat32StayWithinThreeUlpsOverAlphaOfDouble) {
  Kernel k = blend_only_kernel();
  for (std::uint32_t alpha_byte : {1u, 3u, 64u, 254u}) {
    const glm::vec4 layer = k.ha_unpack_rgba(0x40A0FF00u | alpha_byte);
    glm::vec4 c(0.0f);
    glm::dvec4 d(0.0);
    const glm::dvec4 dl(layer);
    for (int i = 0; i < 10000; ++i) {
      c = k.ha_blend_under(c, layer);
      const double w = (1.0 - d.a) * dl.a;
      d = glm::dvec4(glm::dvec3(d) + w * glm::dvec3(dl), d.a + w);
    }
    const double bound = 3.0 * 0x1.0p-24 / dl.a;
    for (int ch = 0; ch < 4; ++ch) EXPECT_LE(std::abs(c[ch] - d[ch]), bound) << "alpha " << alpha_byte << " ch " << ch;
    EXPECT_LE(c.a, 1.0f) << "opacity never exceeds 1";
  }
}

TEST(NumericExtremes, AlphaOneOver255ThroughFourThousandLayersMatchesTheExactReference) {
  BufferConfig cfg = test::config({1, 1}, {128, 128}, Layout::L64, 12);  // AMAX 4095
  HaBuffer b = test::make_buffer(cfg, 4);
  std::vector<Fragment> f;
  for (std::uint32_t i = 0; i < 4000; ++i) f.push_back({0, 0, static_cast<float>(i) / 4096.0f, 0xFFFFFF01u});
  ASSERT_EQ(b.insert(f).failures(), 0u);
  const glm::vec4 got = b.composite(0, 0, glm::vec3(0.0f));
  const auto ref = reference_composite(f, {1, 1}, glm::dvec3(0.0));
  EXPECT_NEAR(got.a, ref[0].a, 3.0 * 0x1.0p-24 * 255.0);
  EXPECT_NEAR(got.a, 1.0 - std::pow(1.0 - 1.0 / 255.0, 4000.0), 1e-4);
}

TEST(NumericExtremes, CoplanarFragmentsMergeDuplicatesAndKeepDistinctColoursLargerDataFirst) {
  HaBuffer b = test::make_buffer(test::config({2, 2}, {16, 16}));
  std::vector<Fragment> f;
  for (std::uint32_t i = 0; i < 40; ++i) f.push_back({1, 1, 0.5f, 0x10u + (i % 10)});  // 10 colours, 4 copies each
  const Counters n = b.insert(test::shuffled(f, 2));
  EXPECT_EQ(n.duplicates, 30u);
  std::vector<ListEntry> list;
  b.list(1, 1, list);
  ASSERT_EQ(list.size(), 10u);
  for (std::uint32_t i = 0; i < 10; ++i) EXPECT_EQ(list[i].data, 0x19u - i);
}

// Linear depth t = (z - near) / (far - near), as the render path maps eye
// depth. The stored code resolves max(2^-D, ulp(t)) in t (t is a float32, so
// for D > 24 bits the float is the limit near t = 1), that is (far - near)
// times that in eye space, whatever the near/far ratio.
TEST(NumericExtremes, NearFarRangesLeaveTheDepthResolutionOfDBitsOrFloat32) {
  for (auto [near, far] : {std::pair{1e-4, 1.0}, std::pair{1.0, 1e6}, std::pair{0.1, 100.0}})
    for (std::uint32_t age_bits : {4u, 8u, 12u}) {
      const RecordLayout l(Layout::L64, age_bits);
      for (double at : {0.001, 0.25, 0.5, 0.99}) {
        const float t0 = static_cast<float>(at);
        const double resolution = std::max(std::ldexp(1.0, -static_cast<int>(l.depth_bits())),
                                           static_cast<double>(std::nextafter(t0, 2.0f) - t0));
        // Two surfaces two resolution steps apart in eye space get distinct codes, nearer larger.
        const double z0 = near + at * (far - near), z1 = z0 + 2.0 * resolution * (far - near);
        const auto t1 = static_cast<float>((z1 - near) / (far - near));
        EXPECT_GT(l.depth_code(t0), l.depth_code(t1)) << near << "/" << far << " D " << l.depth_bits() << " t " << at;
      }
      // Closer than one code step, surfaces may share a code; they are then
      // ordered by data (colour), never by input order (see the coplanar test).
      const float ta = 0.5f, tb = 0.5f + static_cast<float>(0.25 * std::ldexp(1.0, -static_cast<int>(l.depth_bits())));
      EXPECT_GE(l.depth_code(ta), l.depth_code(tb));
    }
}

// Load exactly 1: a table the size of the screen and one fragment per pixel.
// Coherent probing maps the screen one-to-one onto the table at age 1, so
// every record lands at age 1 with no collision at all.
TEST(NumericExtremes, LoadExactlyOneWithOneFragmentPerPixelPlacesEverythingAtAgeOne) {
  const Extent screen{37, 29};
  HaBuffer b = test::make_buffer(test::config(screen, screen), 6);
  std::vector<Fragment> f;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) f.push_back({x, y, 0.5f, x});
  const Counters n = b.insert(test::shuffled(f, 1));
  EXPECT_EQ(n.stored(), screen.area());
  EXPECT_EQ(b.count_stored(), b.slot_count());
  EXPECT_EQ(b.age_histogram()[1], screen.area());
}

TEST(NumericExtremes, ProbesWrapAroundTheTablesLastRowAndColumn) {
  const Extent screen{5, 4}, table{7, 6};
  BufferConfig c = test::config(screen, table, Layout::L64, 4);
  std::vector<glm::uvec2> rows;
  for (std::uint32_t i = 0; i < 15; ++i) rows.emplace_back(6 - (i % 7), 5 - (i / 7) % 6);  // offsets at the far edges
  HaBuffer b(c, OffsetSequence::from_list(table, 15, rows));
  std::vector<Fragment> f;
  for (std::uint32_t i = 0; i < 6; ++i) f.push_back({4, 3, static_cast<float>(i) / 6.0f, i});
  f.push_back({0, 0, 0.5f, 99});
  ASSERT_EQ(b.insert(f).failures(), 0u);
  EXPECT_EQ(test::traversed_lists(b), test::exact_lists(f, b.record_layout()));
  // Pixel (4,3) at age 1 probes ((4 + 6) mod 7, (3 + 5) mod 6) = (3, 2).
  EXPECT_EQ(b.record_layout().age(b.slot(3 + 2 * 7)), 1u);
}

}  // namespace
}  // namespace habuffer
