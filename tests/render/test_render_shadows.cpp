// Translucent shadows in `habuffer render` (habuffer/render/light_pass.h):
// the light buffer built once from the light, every opaque and inserted
// fragment lit times the light's T, exact where the geometry allows,
// identical on both paths, early cull bounded, bad lights refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gl_test_support.h"
#include "habuffer/render/render_job.h"
#include "habuffer/render/shadow_accuracy.h"
#include "habuffer/scene_catalog.h"
#include "habuffer/transmittance_reference.h"

namespace habuffer {
namespace {

using test::gl_context;

// A square in the plane y = height, x and z in [-half, half], tilted about
// the z axis by `tilt` degrees (two triangles).
Mesh square(const std::string& name, float height, float half, float opacity, float tilt = 0.0f) {
  Mesh m;
  m.name = name;
  const float c = std::cos(tilt * 3.14159265f / 180.0f), s = std::sin(tilt * 3.14159265f / 180.0f);
  for (const auto& [x, z] : {std::pair{-half, -half}, {half, -half}, {half, half}, {-half, half}})
    m.positions.push_back({x * c, height + x * s, z});
  m.indices = {0, 1, 2, 0, 2, 3};
  m.opacity = opacity;
  m.colour = glm::vec3(0.9f, 0.6f, 0.3f);
  return m;
}

// Horizontal quads of known opacity over an opaque floor; the light from
// straight above, the camera from below (the floor's underside and the
// quads' lower faces are the surfaces it sees first).
Scene quads_over_floor() {
  Scene s;
  s.name = "quads over a floor";
  s.meshes = {square("quad 0.25", 0.5f, 1.0f, 0.25f), square("quad 0.5", 0.0f, 0.7f, 0.5f),
              square("quad 0.75", -0.5f, 0.4f, 0.75f), square("floor", -1.0f, 1.5f, 1.0f)};
  return s;
}

RenderSettings shadowed(Extent size, glm::vec3 light_direction, Extent light_size, RenderPath path = RenderPath::Gl) {
  RenderSettings s;
  s.path = path;
  s.config.screen = size;
  s.config.table = {};  // auto
  s.camera = {30.0f, -60.0f, 45.0f};
  ShadowSettings shadows;
  shadows.light.direction = light_direction;
  shadows.light.orthographic = true;
  shadows.light.size = light_size;
  s.shadows = shadows;
  return s;
}

ShadowAccuracy accuracy(const Scene& scene, const RenderSettings& s, const RenderResult& r) {
  const TransmittanceReference reference(scene);
  const ShadowReceivers at{&r.camera, s.config.screen, r.fragments, r.opaque_depth};
  return measure_shadow_accuracy(reference, r.light->view, *r.light_buffer,
                                 RecordLayout(Layout::L64, s.shadows->age_bits), r.light->bias_codes, at);
}

TEST(ShadowRender, AnOrthographicLightOverParallelQuadsGivesTheExactProductOutsideTheEdgeBand) {
  gl_context();
  const Scene scene = quads_over_floor();
  RenderSettings s = shadowed({96, 96}, {0.0f, -1.0f, 0.0f}, {128, 128});
  s.shadows->read_back = true;
  s.keep_fragments = true;
  const RenderResult r = render_scene(scene, s);
  ASSERT_TRUE(r.light.has_value());
  EXPECT_EQ(r.light->counters.failures(), 0u);
  const ShadowAccuracy a = accuracy(scene, s, r);
  ASSERT_GT(a.receivers, 2000u);
  // Off the quads' edges T is the product of (1 - alpha8/255) of the quads
  // above, to float rounding; the edges are a thin band.
  EXPECT_EQ(a.within_fraction, 1.0);
  EXPECT_LT(a.max_error_outside, 1e-5);
  EXPECT_LT(static_cast<double>(a.band), 0.15 * static_cast<double>(a.receivers));
  // The floor's underside under all three quads: T = (1 - 64/255)(1 - 128/255)(1 - 191/255).
  const float expected = (1.0f - 64.0f / 255.0f) * (1.0f - 128.0f / 255.0f) * (1.0f - 191.0f / 255.0f);
  EXPECT_NE(std::find_if(r.shadow_map.begin(), r.shadow_map.end(),
                         [&](float t) { return std::abs(t - expected) < 1e-6f; }),
            r.shadow_map.end());
}

TEST(ShadowRender, AnUnoccludedPlaneIsLitEverywhereFacingOrSlantedWithinTheBiasSlope) {
  gl_context();
  for (const float tilt : {0.0f, 30.0f, 60.0f}) {  // tan 60 = 1.73 < the default slope 2
    for (const bool spot : {false, true}) {
      SCOPED_TRACE(std::to_string(tilt) + (spot ? " degrees, spot" : " degrees, directional"));
      Scene scene;
      scene.name = "plane";
      scene.meshes = {square("plane", 0.0f, 1.0f, 1.0f, tilt)};
      RenderSettings s = shadowed({64, 64}, {0.0f, -1.0f, 0.0f}, {96, 96});
      if (spot) s.shadows->light = spot_along(scene, {0.0f, -1.0f, 0.0f}, 60.0f, {96, 96});
      s.camera.pitch = 50.0f;
      const RenderResult r = render_scene(scene, s);
      std::uint64_t covered = 0;
      for (const float t : r.shadow_map) {
        if (t < 0.0f) continue;
        ++covered;
        ASSERT_EQ(t, 1.0f);
      }
      EXPECT_GT(covered, 100u);
    }
  }
}

// The bias rule's residue: a plane steeper than the bias slope shadows
// itself at some pixels, which the accuracy check counts as self_shadow
// (inside the silhouette band); one within the slope never does.
TEST(ShadowRender, APlaneSteeperThanTheBiasSlopeShadowsItselfAndTheCheckCountsIt) {
  gl_context();
  for (const float tilt : {30.0f, 84.0f}) {  // tan 84 = 9.5 > the default slope 2
    SCOPED_TRACE(std::to_string(tilt) + " degrees");
    Scene scene;
    scene.name = "plane";
    scene.meshes = {square("plane", 0.0f, 1.0f, 1.0f, tilt)};
    RenderSettings s = shadowed({64, 64}, {0.0f, -1.0f, 0.0f}, {64, 64});
    s.camera.pitch = 10.0f;
    s.shadows->read_back = true;
    const RenderResult r = render_scene(scene, s);
    const ShadowAccuracy a = accuracy(scene, s, r);
    ASSERT_GT(a.receivers, 100u);
    EXPECT_LE(a.self_shadow, a.silhouette_band);
    if (tilt < 60.0f) EXPECT_EQ(a.self_shadow, 0u);
    else EXPECT_GT(a.self_shadow, 0u);
  }
}

// PCF: where the four light pixels around a receiver agree (off the quads'
// edges) it gives the nearest lookup's T; across an edge, a value between.
TEST(ShadowRender, PcfGivesTheNearestLookupsTOffTheEdgesAndBlendsAcrossThem) {
  gl_context();
  const Scene scene = quads_over_floor();
  const RenderSettings nearest = shadowed({96, 96}, {0.0f, -1.0f, 0.0f}, {128, 128});
  RenderSettings pcf = nearest;
  pcf.shadows->filter = ShadowFilter::Pcf;
  const RenderResult a = render_scene(scene, nearest), b = render_scene(scene, pcf);
  ASSERT_EQ(a.shadow_map.size(), b.shadow_map.size());
  std::size_t covered = 0, equal = 0, between = 0;
  for (std::size_t i = 0; i < a.shadow_map.size(); ++i) {
    if (a.shadow_map[i] < 0.0f) continue;
    ++covered;
    ASSERT_GE(b.shadow_map[i], 0.0f);
    ASSERT_LE(b.shadow_map[i], 1.0f);
    equal += b.shadow_map[i] == a.shadow_map[i];
    between += b.shadow_map[i] != a.shadow_map[i];
  }
  EXPECT_GT(equal, covered * 8 / 10);
  EXPECT_GT(between, 0u);
  // Twice the slope's codes (each rounded up, plus one for rounding).
  EXPECT_NEAR(static_cast<double>(b.light->bias_codes), 2.0 * a.light->bias_codes, 2.0);
}

TEST(ShadowRender, TheLightBufferIsBuiltOnceWhileTheCameraOrbits) {
  gl_context();
  RenderSettings s = shadowed({64, 64}, {-0.3f, -1.0f, 0.2f}, {96, 96});
  s.frames = 3;
  const RenderResult r = render_scene(quads_over_floor(), s);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.light->builds, 1u);
  EXPECT_GT(r.light->counters.stored(), 0u);
  EXPECT_GT(r.light->build_ms, 0.0);
  EXPECT_NE(r.frames[0].yaw, r.frames[2].yaw);
  EXPECT_GT(r.light->lookup_pixels, 0u);
  EXPECT_TRUE(std::any_of(r.shadow_map.begin(), r.shadow_map.end(), [](float t) { return t >= 0.0f && t < 0.5f; }));
}

TEST(ShadowRender, GlAndCpuPathsGiveTheSameShadowedImage) {
  gl_context();
  const Scene scene = quads_over_floor();
  const RenderResult gl = render_scene(scene, shadowed({80, 60}, {-0.3f, -1.0f, 0.2f}, {96, 96}, RenderPath::Gl));
  const RenderResult cpu = render_scene(scene, shadowed({80, 60}, {-0.3f, -1.0f, 0.2f}, {96, 96}, RenderPath::Cpu));
  ASSERT_EQ(gl.image.pixels.size(), cpu.image.pixels.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < gl.image.pixels.size(); ++i) differing += gl.image.pixels[i] != cpu.image.pixels[i];
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(gl.shadow_map, cpu.shadow_map);
  EXPECT_EQ(gl.frames[0].counters, cpu.frames[0].counters);
}

TEST(ShadowRender, EarlyCullOfTheLightBufferErrsByAtMostOneMinusTau) {
  gl_context();
  Scene scene;
  scene.name = "many quads over a floor";
  for (int i = 0; i < 10; ++i) scene.meshes.push_back(square("quad", 0.1f * static_cast<float>(i), 1.0f, 0.4f));
  scene.meshes.push_back(square("floor", -0.5f, 1.5f, 1.0f));
  const RenderSettings exact = shadowed({64, 64}, {0.0f, -1.0f, 0.0f}, {64, 64});
  RenderSettings culled = exact;
  const float tau = 0.9f;
  culled.shadows->early_cull_tau = tau;
  const RenderResult a = render_scene(scene, exact), b = render_scene(scene, culled);
  EXPECT_GT(b.light->counters.culled, 0u);
  ASSERT_EQ(a.shadow_map.size(), b.shadow_map.size());
  float largest = 0.0f;
  for (std::size_t i = 0; i < a.shadow_map.size(); ++i) {
    EXPECT_GE(b.shadow_map[i], a.shadow_map[i]) << "pixel " << i;  // culling only drops records behind
    largest = std::max(largest, b.shadow_map[i] - a.shadow_map[i]);
  }
  EXPECT_GT(largest, 0.0f);
  EXPECT_LE(largest, 1.0f - tau + 1e-6f);
}

TEST(ShadowRender, BadLightsAreRefusedNamingTheParameter) {
  gl_context();
  const Scene scene = quads_over_floor();
  const auto refusal = [&](const RenderSettings& s) -> std::string {
    try {
      (void)render_scene(scene, s);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  RenderSettings s = shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {0, 64});
  EXPECT_NE(refusal(s).find("--light-size 0x64 has no pixels"), std::string::npos) << refusal(s);
  s = shadowed({32, 32}, {0.0f, 0.0f, 0.0f}, {64, 64});
  EXPECT_NE(refusal(s).find("light direction"), std::string::npos) << refusal(s);
  s = shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {64, 64});
  s.shadows->light.orthographic = false;
  s.shadows->light.position = {0.0f, 0.0f, 0.0f};  // inside the scene
  EXPECT_NE(refusal(s).find("inside the scene's bounding sphere"), std::string::npos) << refusal(s);
  s = shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {64, 64});
  s.shadows->early_cull_tau = 1.5f;
  EXPECT_NE(refusal(s).find("--light-cull"), std::string::npos) << refusal(s);
  s.shadows->early_cull_tau = 0.0f;
  s.config.layout = Layout::L32;
  EXPECT_NE(refusal(s).find("--shadows needs --layout 64"), std::string::npos) << refusal(s);
  s = shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {64, 64});
  s.shadows->light.orthographic = false;
  s.shadows->light.position = {1e30f, 0.0f, 0.0f};  // so far that float32 has no depth range left
  EXPECT_NE(refusal(s).find("leaves no usable depth range"), std::string::npos) << refusal(s);
  s = shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {64, 64});
  s.shadows->max_slope = -1.0f;
  EXPECT_NE(refusal(s).find("--shadow-slope"), std::string::npos) << refusal(s);
  EXPECT_THROW((void)render_fragments({}, shadowed({32, 32}, {0.0f, -1.0f, 0.0f}, {64, 64})), std::invalid_argument);
}

// The bias rule's bound, before any GL: a slope of the light map's short
// side in pixels or more (half that under pcf, which doubles the bias) makes
// a bias beyond the whole scene's depth, where no shadow is left (1e30 once
// saturated the bias: every shadow gone, RMSE 0 against the reference).
TEST(ShadowSettings, ASlopeWhoseBiasExceedsTheScenesDepthIsRefusedNamingTheBound) {
  ShadowSettings s;
  s.light.size = {512, 256};
  const auto refusal = [&] {
    try {
      s.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  s.max_slope = 255.0f;
  EXPECT_EQ(refusal(), "accepted");
  s.max_slope = 1e30f;
  EXPECT_NE(refusal().find("--shadow-slope 1e+30 must be below 256"), std::string::npos) << refusal();
  s.max_slope = 256.0f;
  EXPECT_NE(refusal().find("--shadow-slope 256 must be below 256"), std::string::npos) << refusal();
  s.filter = ShadowFilter::Pcf;
  s.max_slope = 127.0f;
  EXPECT_EQ(refusal(), "accepted");
  s.max_slope = 128.0f;
  EXPECT_NE(refusal().find("--shadow-slope 128 must be below 128"), std::string::npos) << refusal();
  EXPECT_NE(refusal().find("--shadow-filter pcf"), std::string::npos) << refusal();
}

// The goal's measurement on a real scene, small enough for CI: outside the
// counted bands, at least 99.9 % of receivers within 1/255 of the reference.
TEST(ShadowRender, EngineReceiversMatchTheRayTracedReferenceOutsideTheBands) {
  gl_context();
  const Scene scene = make_scene("engine", {});
  RenderSettings s = shadowed({128, 128}, {-0.4f, -1.0f, -0.3f}, {512, 512});
  s.camera = {scene.default_yaw, scene.default_pitch, 45.0f};
  s.shadows->read_back = true;
  s.keep_fragments = true;
  const RenderResult r = render_scene(scene, s);
  const ShadowAccuracy a = accuracy(scene, s, r);
  ASSERT_GT(a.receivers, 10000u);
  EXPECT_GE(a.within_fraction, 0.999) << a.band << " of " << a.receivers << " in the bands";
  EXPECT_LT(static_cast<double>(a.band), 0.5 * static_cast<double>(a.receivers));
}

}  // namespace
}  // namespace habuffer
