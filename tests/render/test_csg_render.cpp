// CSG rendered from lossless sorted lists (habuffer/render/csg_renderer.h)
// against the ray caster: coverage and visible primitive equal outside the
// counted edge band; both paths the same; 512 subtracted cylinders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/harness/csg_figure.h"
#include "habuffer/render/csg_renderer.h"
#include "habuffer/solids.h"

namespace habuffer {
namespace {

using test::gl_context;

struct Solids {
  Scene scene;
  std::vector<std::string> names;
  void add(Mesh m) {
    names.push_back(m.name);
    scene.meshes.push_back(std::move(m));
  }
};

// Pixels whose visible primitive (or coverage) differs from the ray caster's outside its band, and the band.
std::pair<std::uint64_t, std::uint64_t> mismatches(const Solids& s, const CsgExpression& e, const CsgRender& r,
                                                    Extent screen) {
  std::vector<bool> band;
  const std::vector<std::int32_t> want = csg_reference(s.scene, e, r.camera, screen, &band);
  std::uint64_t wrong = 0, in_band = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (band[i]) {
      ++in_band;
      continue;
    }
    if (want[i] != r.primitive[i] && wrong < 6)
      ADD_FAILURE() << "pixel " << i % screen.x << "," << i / screen.x << ": gl " << r.primitive[i] << " code "
                    << r.codes[i] << ", reference " << want[i];
    wrong += want[i] != r.primitive[i];
  }
  return {wrong, in_band};
}

Solids cube_minus_cylinders(std::uint32_t n) {
  Solids s;
  s.scene.name = "cube minus cylinders";
  s.add(box_mesh({-1, -1, -1}, {1, 1, 1}, "cube"));
  const std::uint32_t side = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (std::uint32_t k = 0; k < n; ++k) {
    const float x = -0.9f + 1.8f * (static_cast<float>(k % side) + 0.5f) / static_cast<float>(side);
    const float y = -0.9f + 1.8f * (static_cast<float>(k / side) + 0.5f) / static_cast<float>(side);
    std::string name = "c";  // appended, not "c" + ...: GCC 12's -Wrestrict false positive
    name += std::to_string(k);
    s.add(cylinder_mesh({x, y, -1.5f}, {0, 0, 1}, 3.0f, 0.7f / static_cast<float>(side), 12, name));
  }
  return s;
}

std::string minus_all(const Solids& s) {
  std::string text = "cube - (";
  for (std::size_t k = 1; k < s.names.size(); ++k) {
    if (k > 1) text += " | ";
    text += s.names[k];
  }
  text += ")";
  return text;
}

CsgRenderSettings view(Extent screen) {
  CsgRenderSettings r;
  r.screen = screen;
  r.camera = {30.0f, 25.0f, 45.0f};
  return r;
}

// `text` over `s` at 64x64: no pixel off the ray caster's outside its band, a band under a quarter of the image.
void expect_the_ray_casters_pixels(const Solids& s, const char* text) {
  SCOPED_TRACE(text);
  const CsgExpression e = CsgExpression::parse(text, s.names);
  const CsgRender r = render_csg(s.scene, e, view({64, 64}));
  const auto [wrong, band] = mismatches(s, e, r, {64, 64});
  EXPECT_EQ(wrong, 0u);
  EXPECT_LT(band, 64u * 64u / 4);
}

TEST(CsgRender, ACubeMinusCylindersMatchesTheRayCasterOutsideTheEdgeBand) {
  gl_context();
  for (const std::uint32_t n : {1u, 8u, 64u}) {
    SCOPED_TRACE(std::to_string(n) + " cylinders");
    const Solids s = cube_minus_cylinders(n);
    const CsgExpression e = CsgExpression::parse(minus_all(s), s.names);
    const CsgRender r = render_csg(s.scene, e, view({64, 64}));
    EXPECT_EQ(r.counters.failures(), 0u);
    const auto [wrong, band] = mismatches(s, e, r, {64, 64});
    EXPECT_EQ(wrong, 0u);
    EXPECT_LT(band, 64u * 64u / 4);
    // The holes show cylinders' far sides (exits) somewhere.
    EXPECT_TRUE(std::any_of(r.primitive.begin(), r.primitive.end(), [](std::int32_t id) { return id > 0; }));
  }
}

TEST(CsgRender, NestedDifferencesATorusTimesABoxAndTouchingUnionsMatchTheRayCaster) {
  gl_context();
  Solids s;
  s.scene.name = "solids";
  s.add(box_mesh({-1, -1, -1}, {1, 1, 1}, "box"));
  s.add(sphere_mesh({0, 0, 0}, 1.3f, 32, 16, "ball"));
  s.add(box_mesh({-0.4f, -0.4f, -2}, {0.4f, 0.4f, 2}, "bar"));
  s.add(torus_mesh({0, 0, 0}, 1.0f, 0.35f, 32, 16, "ring"));
  s.add(box_mesh({1, -1, -1}, {2, 1, 1}, "next"));  // touches box's +x face
  for (const char* text : {"box - (ball - bar)", "ring & box", "box | next", "(box | next) - bar", "ring - (box & bar)"})
    expect_the_ray_casters_pixels(s, text);
}

// Coplanar faces (a cylinder whose caps lie exactly on the cube's faces) and
// an OpenSCAD-style part: a plate and a post united, minus a hole and a slot.
TEST(CsgRender, CoplanarCapsAndAnOpenScadStylePartMatchTheRayCaster) {
  gl_context();
  Solids s;
  s.scene.name = "part";
  s.add(box_mesh({-1, -1, -1}, {1, 1, 1}, "cube"));
  s.add(cylinder_mesh({0, 0, -1}, {0, 0, 1}, 2.0f, 0.5f, 32, "flush"));  // caps on z = -1 and z = 1
  s.add(box_mesh({-1.5f, -1.5f, -0.2f}, {1.5f, 1.5f, 0.2f}, "plate"));
  s.add(cylinder_mesh({0.8f, 0.8f, 0.2f}, {0, 0, 1}, 1.2f, 0.3f, 24, "post"));
  s.add(cylinder_mesh({-0.8f, -0.8f, -1.0f}, {0, 0, 1}, 2.0f, 0.25f, 24, "hole"));
  s.add(box_mesh({-0.1f, -1.6f, -0.5f}, {0.1f, 0.0f, 0.5f}, "slot"));
  for (const char* text : {"cube - flush", "flush - cube", "(plate | post) - (hole | slot)"})
    expect_the_ray_casters_pixels(s, text);
}

TEST(CsgRender, TheCpuAndGlPathsGiveTheSamePixels) {
  gl_context();
  const Solids s = cube_minus_cylinders(8);
  const CsgExpression e = CsgExpression::parse(minus_all(s), s.names);
  CsgRenderSettings settings = view({48, 40});
  const CsgRender gl = render_csg(s.scene, e, settings);
  settings.cpu = true;
  settings.threads = 2;
  const CsgRender cpu = render_csg(s.scene, e, settings);
  EXPECT_EQ(gl.primitive, cpu.primitive);
  EXPECT_EQ(gl.codes, cpu.codes);
  EXPECT_EQ(gl.counters, cpu.counters);
}

// Issue 34: a size beyond this OpenGL's framebuffer (65535x1) printed the
// driver's raw GL_INVALID_VALUE lines before an error about a "screen"; it is
// refused before any GL object is made, naming --size and the limit, on both paths.
TEST(CsgRender, ASizeBeyondTheOpenGlLimitsIsRefusedNamingTheSizeAndTheLimit) {
  gl_context();
  const Solids s = cube_minus_cylinders(1);
  const CsgExpression e = CsgExpression::parse(minus_all(s), s.names);
  std::vector<std::string> logged;
  gl::set_log_sink([&](const std::string& m) { logged.push_back(m); });
  for (const bool cpu : {false, true}) {
    CsgRenderSettings settings = view({65535, 1});
    settings.cpu = cpu;
    try {
      (void)render_csg(s.scene, e, settings);
      ADD_FAILURE() << "a 65535x1 image was accepted";
    } catch (const gl::GlError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find("csg: --size 65535x1 exceeds this OpenGL's largest "), std::string::npos) << what;
      EXPECT_NE(what.find("(GL_MAX_"), std::string::npos) << what;
    }
  }
  gl::discard_gl_errors();
  gl::set_log_sink([](const std::string& m) { std::fprintf(stderr, "habuffer gl: %s\n", m.c_str()); });  // the default
  for (const std::string& m : logged) ADD_FAILURE() << "GL said: " << m;
}

TEST(CsgRender, FiveHundredTwelveSubtractedCylindersRenderLosslessly) {
  gl_context();
  const Solids s = cube_minus_cylinders(512);
  const CsgExpression e = CsgExpression::parse(minus_all(s), s.names);
  EXPECT_EQ(e.primitives(), 513u);
  const CsgRender r = render_csg(s.scene, e, view({64, 64}));
  EXPECT_EQ(r.counters.failures(), 0u);
  EXPECT_GT(r.counters.stored(), 0u);
  const auto [wrong, band] = mismatches(s, e, r, {64, 64});
  EXPECT_EQ(wrong, 0u);
  const CsgExpression other = CsgExpression::parse("a", std::vector<std::string>{"a"});
  EXPECT_THROW((void)render_csg(s.scene, other, view({16, 16})), CsgError);
}

TEST(CsgRender, TheFiguresCurveHasOneRowPerCylinderCountWithoutMismatch) {
  gl_context();
  harness::CsgFigureSettings f;
  f.cylinders = {1, 9};
  f.size = {32, 32};
  f.repeats = 1;
  const harness::ResultTable t = harness::run_csg_figure(f);
  ASSERT_EQ(t.rows.size(), 2u);
  for (const harness::ResultRow& r : t.rows) EXPECT_EQ(r.number("mismatches"), 0.0);
  EXPECT_EQ(t.rows[1].number("primitives"), 10.0);
  EXPECT_THROW((void)harness::csg_cylinders(0), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
