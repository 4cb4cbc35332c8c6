// Translucent shadow maps' lookup (habuffer/transmittance.h, seed 000
// section 6): the transmittance of a receiver through a light buffer's
// records, exact over known stacks, the same through every exact technique
// and through the HA-buffer's shared GLSL walk, bounded under early cull.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "habuffer/lossless_build.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/transmittance.h"
#include "habuffer/opacity_shadow_map.h"
#include "test_support.h"

namespace habuffer {
namespace {

OffsetSource random_offsets(std::uint64_t seed) {
  OffsetSource s;
  s.generator = OffsetGenerator::Random;
  s.seed = seed;
  return s;
}

// An axis-aligned quad of the light's view: pixels [x0, x1) x [y0, y1) at
// depth t, with opacity alpha (8 bits).
struct Quad {
  std::uint32_t x0, y0, x1, y1;
  float t;
  std::uint32_t alpha;
  [[nodiscard]] bool covers(std::uint32_t x, std::uint32_t y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

std::vector<Fragment> rasterize(const std::vector<Quad>& quads, Extent screen) {
  std::vector<Fragment> out;
  for (const Quad& q : quads)
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x)
        if (q.covers(x, y)) out.push_back({x, y, q.t, 0x80402000u | q.alpha});
  return out;
}

// T by the formula, in float32, nearest first: the quads at (x, y) strictly
// nearer than the receiver's code plus the bias.
float expected_t(const std::vector<Quad>& quads, std::uint32_t x, std::uint32_t y, std::uint32_t code,
                 std::uint32_t bias, const RecordLayout& layout) {
  std::vector<const Quad*> front;
  for (const Quad& q : quads)
    if (q.covers(x, y) && layout.depth_code(q.t) > std::uint64_t{code} + bias) front.push_back(&q);
  std::sort(front.begin(), front.end(), [](const Quad* a, const Quad* b) { return a->t < b->t; });
  float t = 1.0f;
  for (const Quad* q : front) t *= 1.0f - static_cast<float>(q->alpha) * (1.0f / 255.0f);
  return t;
}

// Every technique that stores exact lists, its capacity enough for `fragments`.
std::vector<TechniqueConfig> exact_light_buffers(Extent screen, std::size_t fragments, std::uint32_t depth) {
  std::vector<TechniqueConfig> out;
  for (const TechniqueDescriptor* d : technique_registry()) {
    if (!d->stores_lists || !d->exact) continue;
    TechniqueConfig c = test::technique_config(d->technique, screen);
    c.buffer.table = {screen.x * 2, screen.y * 2};
    c.pool_capacity = fragments * 4 + 64;  // pages of 4 for paged lists
    c.layers = depth;
    out.push_back(c);
  }
  return out;
}

TEST(Transmittance, ParallelQuadsGiveTheProductOfOneMinusAlphaOfThoseInFrontOnEveryTechnique) {
  const Extent screen{24, 20};
  const std::vector<Quad> quads = {{0, 0, 24, 20, 0.25f, 32},  {4, 2, 20, 18, 0.375f, 128}, {8, 6, 16, 14, 0.5f, 255},
                                   {2, 10, 22, 19, 0.625f, 1}, {0, 0, 12, 10, 0.75f, 200}};
  const std::vector<Fragment> frags = rasterize(quads, screen);
  const RecordLayout layout{Layout::L64, 8};
  const std::vector<float> receivers = {0.125f, 0.25f, 0.3f, 0.5f, 0.6f, 0.875f, 1.0f};
  for (const TechniqueConfig& c : exact_light_buffers(screen, frags.size(), 5)) {
    SCOPED_TRACE(to_string(c.technique));
    const auto light = make_fragment_buffer(c, random_offsets(3));
    ASSERT_EQ(light->insert(frags).failures(), 0u);
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x)
        for (const float r : receivers)
          for (const std::uint32_t bias : {0u, 1u}) {
            const std::uint32_t code = layout.depth_code(r);
            ASSERT_EQ(transmittance(*light, x, y, code, bias), expected_t(quads, x, y, code, bias, layout))
                << "pixel " << x << "," << y << " receiver " << r << " bias " << bias;
          }
  }
}

// The HA-buffer's lookup is the shared GLSL walk (the GPU path's code); it
// gives what the lists give, bit for bit, over random stacks and layouts of
// its table.
TEST(Transmittance, TheHaBuffersSharedWalkGivesWhatItsListsGiveOverSeeds) {
  const Extent screen{17, 13};
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::vector<Fragment> frags = test::grid_stream(screen, 900, seed, 1);
    BufferConfig c = test::config(screen, {48, 40});  // load under 0.5
    HaBuffer light(c, random_offsets(seed).make(c.table, c.record_layout().max_age()));
    ASSERT_EQ(light.insert(frags).failures(), 0u);
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x)
        for (std::uint32_t code : {0u, 1u << 10, 1u << 20, (1u << 24) - 1})
          ASSERT_EQ(light.transmittance(x, y, code, 3), transmittance(light, x, y, code, 3)) << seed;
  }
}

// A receiver on an opaque plane facing the light is not shadowed by the
// plane's own records (T = 1 everywhere: no acne), one behind it is fully
// shadowed (T = 0), with bias 0.
TEST(Transmittance, AnUnoccludedPlaneFacingTheLightIsLitEverywhereAndWhatIsBehindItIsNot) {
  const Extent screen{32, 32};
  const std::vector<Quad> plane = {{0, 0, 32, 32, 0.5f, 255}};
  BufferConfig c = test::config(screen, screen);
  HaBuffer light(c, random_offsets(1).make(c.table, c.record_layout().max_age()));
  ASSERT_EQ(light.insert(rasterize(plane, screen)).failures(), 0u);
  const RecordLayout layout = c.record_layout();
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) {
      EXPECT_EQ(light.transmittance(x, y, layout.depth_code(0.5f), 0), 1.0f);
      EXPECT_EQ(light.transmittance(x, y, layout.depth_code(0.5f + 0x1.0p-20f), 0), 0.0f);
    }
}

// The bias in codes: a record nearer than the receiver by at most the bias
// is the receiver's own surface and does not shadow it; one a code further
// does.
TEST(Transmittance, ARecordWithinTheBiasOfTheReceiverDoesNotShadowItAndOneBeyondItDoes) {
  const std::vector<ListEntry> list = {{0, 1000, 0xFFFFFF80u}, {0, 900, 0xFFFFFF40u}};
  const float half = 1.0f - 128.0f * (1.0f / 255.0f);
  EXPECT_EQ(list_transmittance(list, 990, 10), 1.0f);   // 1000 <= 990 + 10: its own
  EXPECT_EQ(list_transmittance(list, 989, 10), half);   // 1000 > 999
  EXPECT_EQ(list_transmittance(list, 0, 0), half * (1.0f - 64.0f * (1.0f / 255.0f)));
  EXPECT_EQ(list_transmittance(list, 0xFFFFFFFFu, 0xFFFFFFFFu), 1.0f);  // no wrap
  EXPECT_EQ(list_transmittance({}, 0, 0), 1.0f);
}

// Early cull with threshold tau keeps a pixel's records until their
// opacity reaches tau, so the transmittance it gives differs from the exact
// one by at most 1 - tau (both are at most 1 - tau beyond that point).
TEST(Transmittance, EarlyCullChangesTheTransmittanceByAtMostOneMinusTau) {
  const Extent screen{16, 16};
  for (const float tau : {0.5f, 0.9f, 0.99f})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const std::vector<Fragment> frags = test::grid_stream(screen, 2000, seed, 16);
      BufferConfig exact_config = test::config(screen, {64, 64}), cull_config = exact_config;  // load 0.49
      cull_config.early_cull_tau = tau;
      HaBuffer exact(exact_config, random_offsets(seed).make(exact_config.table, exact_config.record_layout().max_age()));
      HaBuffer culled(cull_config, random_offsets(seed).make(cull_config.table, cull_config.record_layout().max_age()));
      ASSERT_EQ(exact.insert(frags).failures(), 0u);
      ASSERT_GT(culled.insert(frags).culled, 0u);  // the bound is tested on records early cull dropped
      float worst = 0.0f, changed = 0.0f;
      for (std::uint32_t y = 0; y < screen.y; ++y)
        for (std::uint32_t x = 0; x < screen.x; ++x)
          for (std::uint32_t code : {0u, 1u << 12, 1u << 22}) {
            const float d = std::abs(exact.transmittance(x, y, code, 0) - culled.transmittance(x, y, code, 0));
            worst = std::max(worst, d);
            changed += d > 0.0f ? 1.0f : 0.0f;
          }
      EXPECT_LE(worst, 1.0f - tau + 1e-6f) << "tau " << tau << " seed " << seed;
      EXPECT_GT(changed, 0.0f) << "early cull changed no transmittance: the bound was not exercised";
    }
}

// The k-buffer as the approximate light buffer: it keeps each pixel's K
// nearest records, so a receiver's product has the same leading factors and
// possibly fewer: its T is never below the exact one, equals it at pixels
// that did not overflow, and differs somewhere when pixels did.
TEST(Transmittance, TheKBuffersTransmittanceIsNeverBelowTheExactOneAndEqualWhereNothingOverflowed) {
  const Extent screen{16, 12};
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const std::vector<Fragment> frags = test::grid_stream(screen, 1500, seed, 8);
    BufferConfig c = test::config(screen, {48, 48});
    HaBuffer exact(c, random_offsets(seed).make(c.table, c.record_layout().max_age()));
    ASSERT_EQ(exact.insert(frags).failures(), 0u);
    TechniqueConfig kc = test::technique_config(Technique::KBuffer, screen);
    kc.layers = 4;
    const auto kbuffer = make_fragment_buffer(kc, {});
    ASSERT_GT(kbuffer->insert(frags).dropped_layers, 0u);
    int differ = 0;
    std::vector<ListEntry> list;
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x) {
        exact.list(x, y, list);
        const bool overflowed = list.size() > kc.layers;
        for (std::uint32_t code : {0u, 1u << 12, 1u << 20, 1u << 23}) {
          const float want = exact.transmittance(x, y, code, 0), approx = transmittance(*kbuffer, x, y, code, 0);
          EXPECT_GE(approx, want) << x << "," << y;
          if (!overflowed) {
            EXPECT_EQ(approx, want) << x << "," << y;
          }
          differ += approx != want ? 1 : 0;
        }
      }
    EXPECT_GT(differ, 0) << "no receiver saw the k-buffer's missing records";
  }
}

TEST(Transmittance, ALightBufferWithoutOpacityOrListsIsRefusedByName) {
  const Extent screen{8, 8};
  BufferConfig l32 = test::config(screen, screen, Layout::L32);
  HaBuffer ha32(l32, random_offsets(1).make(l32.table, l32.record_layout().max_age()));
  EXPECT_THROW((void)ha32.transmittance(0, 0, 0, 0), std::invalid_argument);
  try {
    (void)transmittance(ha32, 0, 0, 0, 0);
    ADD_FAILURE() << "an L32 light buffer was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("L64"), std::string::npos) << e.what();
  }
  const auto wboit = make_fragment_buffer(test::technique_config(Technique::Wboit, screen), {});
  try {
    (void)transmittance(*wboit, 0, 0, 0, 0);
    ADD_FAILURE() << "wboit was taken as a light buffer";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("wboit stores no lists"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace habuffer

namespace habuffer {
namespace {

// 2x2 percentage-closer filtering: bilinear between the four light pixels
// around the window position, the nearest pixel's T at its centre, clamped
// at the map's edge.
TEST(Transmittance, PercentageCloserFilteringWeighsTheFourPixelsAroundThePointBilinearly) {
  const Extent screen{2, 2};
  const std::vector<Quad> quads = {{0, 0, 1, 2, 0.25f, 128}};  // the left column, alpha 128
  TechniqueConfig c = test::technique_config(Technique::Ha, screen);
  c.buffer.table = {4, 4};
  const TechniqueBuild b = build_technique(c, random_offsets(1), rasterize(quads, screen), InsertOptions{});
  const RecordLayout layout = c.buffer.record_layout();
  const std::uint32_t code = layout.depth_code(0.75f);
  const float shadowed = 1.0f - 128.0f / 255.0f;
  EXPECT_EQ(transmittance_pcf(*b.buffer, 0.5f, 0.5f, code, 0), shadowed);  // a pixel's centre: its own T
  EXPECT_EQ(transmittance_pcf(*b.buffer, 1.5f, 1.5f, code, 0), 1.0f);
  EXPECT_FLOAT_EQ(transmittance_pcf(*b.buffer, 1.0f, 1.0f, code, 0), 0.5f * (shadowed + 1.0f));  // halfway
  EXPECT_FLOAT_EQ(transmittance_pcf(*b.buffer, 0.75f, 0.6f, code, 0), 0.75f * shadowed + 0.25f);
  EXPECT_EQ(transmittance_pcf(*b.buffer, 0.1f, 0.1f, code, 0), shadowed);  // clamped at the edge
  EXPECT_FLOAT_EQ(transmittance_pcf(*b.buffer, 1.99f, 0.2f, code, 0), 1.0f);
}

// The opacity shadow map baseline: exact at its planes, linear between them,
// and refusing what it cannot hold.
TEST(OpacityShadowMap, PlanesHoldTheProductInFrontAndReceiversBetweenThemInterpolate) {
  OpacityShadowMap map({2, 1}, 4);  // planes at t = 0, 0.25, 0.5, 0.75, 1
  const Fragment layers[] = {{0, 0, 0.1f, 0xFFFFFF80u}, {0, 0, 0.6f, 0xFFFFFF40u}, {1, 0, 0.3f, 0xFFFFFFFFu}};
  map.insert(layers);
  const float a = 1.0f - 128.0f / 255.0f, b = 1.0f - 64.0f / 255.0f;
  EXPECT_EQ(map.transmittance(0, 0, 0.0f), 1.0f);
  EXPECT_EQ(map.transmittance(0, 0, 0.25f), a);
  EXPECT_EQ(map.transmittance(0, 0, 0.5f), a);
  EXPECT_EQ(map.transmittance(0, 0, 1.0f), a * b);
  EXPECT_FLOAT_EQ(map.transmittance(0, 0, 0.125f), 0.5f * (1.0f + a));  // halfway through the first slice
  EXPECT_EQ(map.transmittance(1, 0, 0.5f), 0.0f);                       // an opaque fragment in front
  EXPECT_EQ(map.memory_bytes(), 2u * 5u * sizeof(float));
  EXPECT_THROW(OpacityShadowMap({0, 4}, 4), std::invalid_argument);
  EXPECT_THROW(OpacityShadowMap({4, 4}, 0), std::invalid_argument);
  const Fragment off[] = {{2, 0, 0.5f, 1u}};
  EXPECT_THROW(map.insert(off), std::out_of_range);
  const Fragment deep[] = {{0, 0, 1.5f, 1u}};
  EXPECT_THROW(map.insert(deep), std::invalid_argument);
  EXPECT_THROW((void)map.transmittance(0, 1, 0.5f), std::out_of_range);
}

}  // namespace
}  // namespace habuffer
