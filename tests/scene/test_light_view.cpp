// The light of a translucent shadow map (habuffer/light_view.h): framed on
// the scene, mapping world points to light pixels and depths, refusing bad
// parameters by name; with the transmittance lookup, exact over parallel
// quads seen by an orthographic light.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "habuffer/light_view.h"
#include "habuffer/lossless_build.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/random.h"
#include "habuffer/transmittance.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer {
namespace {

// Square quads in planes z = zs[i] (x, y in [-1, 1]), two triangles each.
Scene stacked_quads(const std::vector<float>& zs) {
  Scene s;
  s.name = "stacked quads";
  for (std::size_t i = 0; i < zs.size(); ++i) {
    Mesh m;
    m.name = "quad " + std::to_string(i);
    const float z = zs[i];
    m.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    m.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(m);
  }
  return s;
}

std::string refusal(const Scene& scene, const LightParams& p) {
  try {
    (void)frame_light(scene, p);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LightView, AnOrthographicLightSeesEveryVertexAndMapsItsRaysToOnePixelWithGrowingDepth) {
  const Scene scene = stacked_quads({0.5f, 0.0f, -0.5f});
  LightParams p;
  p.direction = {0.3f, -0.2f, -1.0f};
  p.size = {64, 48};
  const LightView light = frame_light(scene, p);
  for (const Mesh& m : scene.meshes)
    for (const glm::vec3& v : m.positions) ASSERT_TRUE(light.sample(v).has_value());
  const glm::vec3 dir = glm::normalize(p.direction);
  const glm::vec3 a{0.1f, 0.2f, 0.3f};
  const auto near_sample = light.sample(a), far_sample = light.sample(a + dir * 0.5f);
  ASSERT_TRUE(near_sample && far_sample);
  EXPECT_EQ(near_sample->pixel, far_sample->pixel);
  EXPECT_LT(near_sample->depth, far_sample->depth);
  EXPECT_FALSE(light.sample(a + dir * 100.0f).has_value());  // beyond the far plane
}

TEST(LightView, BadLightsAreRefusedNamingTheParameter) {
  const Scene scene = stacked_quads({0.0f});
  LightParams zero;
  zero.direction = glm::vec3(0.0f);
  EXPECT_NE(refusal(scene, zero).find("light direction"), std::string::npos);
  LightParams empty;
  empty.size = {0, 16};
  EXPECT_NE(refusal(scene, empty).find("light map size 0x16"), std::string::npos);
  LightParams inside;
  inside.orthographic = false;
  inside.position = {0.0f, 0.0f, 0.2f};
  EXPECT_NE(refusal(scene, inside).find("inside the scene's bounding sphere"), std::string::npos);
  LightParams narrow;
  narrow.orthographic = false;
  narrow.position = {0.0f, 0.0f, 3.0f};
  narrow.fov = 10.0f;
  EXPECT_NE(refusal(scene, narrow).find("light fov 10"), std::string::npos);
  LightParams spot = narrow;
  spot.fov = 90.0f;
  spot.direction = glm::vec3(0.0f);  // a spot aims at the scene's centre: its direction is not read
  EXPECT_EQ(refusal(scene, spot), "accepted");
  EXPECT_NE(refusal(Scene{}, LightParams{}).find("no vertices"), std::string::npos);
}

// An orthographic light along -z over parallel quads of known opacity: the
// light buffer built from the quads' points at each light pixel's centre
// gives, for a receiver behind them, the product of (1 - alpha8 / 255) of
// the quads in front at every pixel, and 1 on the receiver's own plane.
TEST(LightView, ParallelQuadsUnderAnOrthographicLightGiveTheExactTransmittanceAtEveryPixel) {
  const std::vector<float> zs = {0.6f, 0.2f, -0.2f, -0.6f};  // the last is the receiver
  const std::uint32_t alphas[] = {40, 128, 255 / 3, 255};
  const Scene scene = stacked_quads(zs);
  LightParams p;
  p.direction = {0.0f, 0.0f, -1.0f};
  p.size = {32, 32};
  const LightView light = frame_light(scene, p);
  // Each quad's point under each light pixel's centre, as a rasterizer samples it.
  std::vector<Fragment> frags;
  std::vector<std::pair<glm::uvec2, float>> receiver;
  const float width = 2.0f / light.camera.projection[0][0];
  for (std::uint32_t y = 0; y < p.size.y; ++y)
    for (std::uint32_t x = 0; x < p.size.x; ++x) {
      const float wx = (static_cast<float>(x) + 0.5f) / static_cast<float>(p.size.x) * width - width * 0.5f;
      const float wy = (static_cast<float>(y) + 0.5f) / static_cast<float>(p.size.y) * width - width * 0.5f;
      const glm::vec3 centre = scene.bounds().centre();
      for (std::size_t i = 0; i < zs.size(); ++i) {
        const glm::vec3 w{centre.x + wx, centre.y + wy, zs[i]};
        if (std::abs(w.x) > 1.0f || std::abs(w.y) > 1.0f) continue;
        const auto s = light.sample(w);
        ASSERT_TRUE(s.has_value());
        ASSERT_EQ(s->pixel, glm::uvec2(x, y));
        frags.push_back({x, y, s->depth, 0xC0C0C000u | alphas[i]});
        if (i + 1 == zs.size()) receiver.emplace_back(s->pixel, s->depth);
      }
    }
  BufferConfig c;
  c.screen = p.size;
  c.table = {48, 48};
  OffsetSource offsets;
  HaBuffer buffer(c, offsets.make(c.table, c.record_layout().max_age()));
  ASSERT_EQ(buffer.insert(frags).failures(), 0u);
  ASSERT_FALSE(receiver.empty());
  float in_front = 1.0f;
  for (int i = 0; i < 3; ++i) in_front *= 1.0f - static_cast<float>(alphas[i]) * (1.0f / 255.0f);
  const RecordLayout layout = c.record_layout();
  for (const auto& [pixel, depth] : receiver) {
    EXPECT_EQ(buffer.transmittance(pixel.x, pixel.y, layout.depth_code(depth), 0), in_front);
    EXPECT_EQ(transmittance(buffer, pixel.x, pixel.y, layout.depth_code(depth), 0), in_front);
  }
  // The ray-traced reference agrees, in double, at the receiver's points
  // (the quads' opacities as the gather packs them).
  Scene coloured = scene;
  for (std::size_t i = 0; i < coloured.meshes.size(); ++i)
    coloured.meshes[i].opacity = static_cast<float>(alphas[i]) / 255.0f;
  const TransmittanceReference reference(coloured);
  for (const glm::vec3 w : {glm::vec3(0.1f, -0.3f, zs[3]), glm::vec3(-0.97f, 0.97f, zs[3])})
    EXPECT_NEAR(reference.transmittance(glm::dvec3(w), light, 1e-9), in_front, 1e-6);
  // The nearest quad is lit (nothing in front, its own record excluded).
  for (const glm::vec3 w : {glm::vec3(0.0f, 0.0f, zs[0]), glm::vec3(-0.9f, 0.7f, zs[0]), glm::vec3(0.95f, -0.95f, zs[0])}) {
    const auto s = light.sample(w);
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(buffer.transmittance(s->pixel.x, s->pixel.y, layout.depth_code(s->depth), 0), 1.0f);
  }
}

// The reference's hierarchy finds every hit the brute force finds: random
// triangle soups, random points, directional and spot lights.
TEST(TransmittanceReference, TheHierarchyGivesWhatTestingEveryTriangleGivesOverSeeds) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SplitMix64 rng(seed);
    const auto unit = [&] { return static_cast<float>(rng.below(1u << 20)) * 0x1.0p-19f - 1.0f; };
    Scene soup;
    soup.name = "soup";
    for (int m = 0; m < 5; ++m) {
      Mesh mesh;
      mesh.name = std::to_string(m);
      mesh.opacity = 0.1f + 0.2f * static_cast<float>(m);
      for (int t = 0; t < 60; ++t) {
        const glm::vec3 c{unit(), unit(), unit()};
        for (int k = 0; k < 3; ++k) {
          mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
          mesh.positions.push_back(c + 0.3f * glm::vec3(unit(), unit(), unit()));
        }
      }
      soup.meshes.push_back(mesh);
    }
    const TransmittanceReference reference(soup);
    ASSERT_EQ(reference.triangles(), 300u);
    LightParams directional;
    directional.direction = {unit(), -1.0f, unit()};
    LightParams spot;
    spot.orthographic = false;
    spot.position = {0.5f, 4.0f, -0.5f};
    spot.fov = 90.0f;
    int shadowed = 0;
    for (const LightParams& p : {directional, spot}) {
      const LightView light = frame_light(soup, p);
      for (int i = 0; i < 200; ++i) {
        const glm::dvec3 point{unit(), unit(), unit()};
        const double fast = reference.transmittance(point, light, 1e-9);
        EXPECT_NEAR(fast, reference.transmittance_brute_force(point, light, 1e-9), 1e-12) << seed;
        shadowed += fast < 1.0 ? 1 : 0;
      }
    }
    EXPECT_GT(shadowed, 0);
    EXPECT_THROW((void)reference.transmittance(glm::dvec3(0.0), frame_light(soup, directional), -1.0),
                 std::invalid_argument);
  }
}

TEST(LightView, TheSlopeBiasGrowsWithTheSlopeAndThePixelSize) {
  const Scene scene = stacked_quads({0.5f, -0.5f});
  LightParams p;
  p.direction = {0.0f, 0.0f, -1.0f};
  p.size = {256, 256};
  const LightView fine = frame_light(scene, p);
  p.size = {64, 64};
  const LightView coarse = frame_light(scene, p);
  EXPECT_LT(shadow_bias_codes(fine, 1.0f, 24), shadow_bias_codes(coarse, 1.0f, 24));
  EXPECT_LT(shadow_bias_codes(coarse, 0.5f, 24), shadow_bias_codes(coarse, 2.0f, 24));
  EXPECT_EQ(shadow_bias_codes(coarse, 0.0f, 24), 1u);
  EXPECT_THROW((void)shadow_bias_codes(coarse, -1.0f, 24), std::invalid_argument);
  EXPECT_THROW((void)shadow_bias_codes(coarse, std::nanf(""), 24), std::invalid_argument);
  EXPECT_THROW((void)shadow_bias_codes(coarse, 1.0f, 0), std::invalid_argument);
}

// The bias is max_slope light pixels' sides; from the map's short side in
// pixels on it exceeds the frustum's short side, which holds the scene:
// nothing could shadow anything (1e30 once saturated the bias silently).
TEST(LightView, ASlopeWhoseBiasExceedsTheMapsShortSideIsRefused) {
  EXPECT_EQ(shadow_slope_limit({64, 48}), 48.0);
  const Scene scene = stacked_quads({0.5f, -0.5f});
  LightParams p;
  p.direction = {0.0f, 0.0f, -1.0f};
  p.size = {64, 48};
  const LightView light = frame_light(scene, p);
  EXPECT_GT(shadow_bias_codes(light, 47.0f, 24), 1u);
  for (const float slope : {48.0f, 1000.0f, 1e30f}) {
    try {
      (void)shadow_bias_codes(light, slope, 24);
      ADD_FAILURE() << "slope " << slope << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("is not below 48"), std::string::npos) << e.what();
    }
  }
}

// Any finite direction but zero is a direction: scaled by its largest
// component before it is normalised, 1e38 or 1e-40 neither overflows nor
// underflows (glm::length of them once said "not finite" or zero).
TEST(LightView, AnyFiniteNonZeroDirectionIsNormalisedHoweverLongOrShort) {
  const Scene scene = stacked_quads({0.5f, -0.5f});
  for (const glm::vec3 d : {glm::vec3(1e38f, -1e38f, 0.0f), glm::vec3(3e38f, -3e38f, 3e38f),
                            glm::vec3(0.0f, 0.0f, -1e-40f), glm::vec3(2e-30f, -3e-30f, -1e-30f)}) {
    SCOPED_TRACE(std::to_string(d.x) + ", " + std::to_string(d.y) + ", " + std::to_string(d.z));
    LightParams p;
    p.direction = d;
    p.size = {64, 64};
    EXPECT_EQ(refusal(scene, p), "accepted");
    const glm::dvec3 expected = glm::normalize(glm::dvec3(d));
    const LightView light = frame_light(scene, p);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(light.direction[i], expected[i], 1e-6);
    const LightParams spot = spot_along(scene, d, 60.0f, {64, 64});
    EXPECT_EQ(refusal(scene, spot), "accepted");
    EXPECT_LT(glm::length(glm::dvec3(spot.position) - glm::dvec3(scene.bounds().centre())), 10.0);
  }
  LightParams bad;
  bad.direction = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f};
  EXPECT_NE(refusal(scene, bad).find("is not finite"), std::string::npos) << refusal(scene, bad);
  bad.direction = glm::vec3(0.0f);
  EXPECT_NE(refusal(scene, bad).find("is the zero vector"), std::string::npos) << refusal(scene, bad);
}

// The precision rule (kLightDepthRounding): float32 rounds the light's depth
// by up to 4 ulps of the largest coordinate its view handles; past one light
// pixel's side at the far plane (2^21 sides from the origin) the light is
// refused. Quads of radius 1.5: one pixel is about 3.06 / map side, so the
// limit is about 6300 at 1024 pixels and 1600 at 4096.
TEST(LightView, ALightWhoseFloat32DepthRoundsBeyondALightPixelIsRefused) {
  const Scene scene = stacked_quads({0.5f, -0.5f});
  const auto spot = [](float distance, std::uint32_t side) {
    LightParams p;
    p.orthographic = false;
    p.position = {0.0f, 0.0f, distance};
    p.size = {side, side};
    return p;
  };
  EXPECT_EQ(refusal(scene, spot(1e3f, 1024)), "accepted");
  EXPECT_EQ(refusal(scene, spot(3e3f, 1024)), "accepted");
  EXPECT_NE(refusal(scene, spot(3e3f, 4096)).find("too coarse a depth"), std::string::npos);  // finer pixels
  const std::string far = refusal(scene, spot(1e5f, 1024));  // a usable depth range, but 16 times the rule's rounding
  EXPECT_NE(far.find("light position"), std::string::npos) << far;
  EXPECT_NE(far.find("leaves float32 too coarse a depth"), std::string::npos) << far;
  EXPECT_NE(far.find("of the origin (2^21 light pixels)"), std::string::npos) << far;
  // A directional light over a scene far from the origin: the view's terms are that large too.
  const auto shifted = [&](float by) {
    Scene s = scene;
    for (Mesh& m : s.meshes)
      for (glm::vec3& v : m.positions) v.x += by;
    return s;
  };
  LightParams directional;
  directional.direction = {0.3f, -0.2f, -1.0f};
  EXPECT_EQ(refusal(shifted(1e3f), directional), "accepted");
  const std::string shifted_far = refusal(shifted(1e5f), directional);
  EXPECT_NE(shifted_far.find("light direction"), std::string::npos) << shifted_far;
  EXPECT_NE(shifted_far.find("too coarse a depth"), std::string::npos) << shifted_far;
}

}  // namespace
}  // namespace habuffer
