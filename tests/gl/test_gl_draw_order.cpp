// The draw-order test on the GPU path: every exact technique resolves a
// scene drawn in one order and in the reverse order to the same image bit
// for bit and reads back the same lists CSV, in both atomic modes llvmpipe
// runs; wboit and blend move within their stated bound (test_draw_order.cpp
// is the CPU path's).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gl_test_support.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/interchange.h"
#include "habuffer/lossless_build.h"

namespace habuffer {
namespace {

struct Rendered {
  gl::FrameReport report;
  std::vector<glm::vec4> image;
  std::string lists_csv;
};

Rendered render(const TechniqueConfig& c, gl::AtomicMode mode, std::span<const Fragment> frags) {
  gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, mode));
  Rendered r;
  r.report = gl::ComputeInserter(gpu).insert(frags);
  r.image = test::resolve_to_image(gpu, glm::vec3(0.25f, 0.5f, 0.75f));
  if (stores_lists(c.technique)) {
    // One file per process and test: ctest runs the tests side by side.
    const std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) /
        ("gl_draw_order_lists_" + std::to_string(::getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv");
    write_lists(path.string(), *gpu.technique().read_back());
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    r.lists_csv = s.str();
    std::filesystem::remove(path);
  }
  return r;
}

TechniqueConfig sized(Technique t, Extent screen, std::span<const Fragment> frags, gl::AtomicMode mode) {
  TechniqueConfig c = test::technique_config(t, screen, test::layout_of(mode));
  c.buffer.table = {screen.x * 4, screen.y * 4};
  c.pool_capacity = frags.size() * 4;  // room for every pool technique: paged lists ask a page of 4 nodes at most per fragment
  c.layers = test::depth_complexity(frags, screen);
  return c;
}

class GlDrawOrder : public ::testing::Test {
 protected:
  void SetUp() override { test::gl_context(); }
};

TEST_F(GlDrawOrder, EveryExactTechniqueResolvesTheReversedDrawOrderToTheSameImageBitForBitOnTheGpu) {
  const Extent screen{32, 24};
  const std::vector<Fragment> frags = test::draw_order_scene(screen, 4000, 5);
  const std::vector<Fragment> reversed(frags.rbegin(), frags.rend());
  for (gl::AtomicMode mode : {gl::AtomicMode::Native32, gl::AtomicMode::Emulated64})
    for (Technique t : all_techniques()) {
      if (!exact_technique(t)) continue;
      SCOPED_TRACE(to_string(t) + " " + to_string(mode));
      const TechniqueConfig c = sized(t, screen, frags, mode);
      const Rendered a = render(c, mode, frags), b = render(c, mode, reversed);
      ASSERT_EQ(a.report.counters.failures(), 0u);
      EXPECT_EQ(a.report.counters, b.report.counters);
      EXPECT_TRUE(test::same_bits(a.image, b.image));
      EXPECT_FALSE(a.lists_csv.empty());
      EXPECT_EQ(a.lists_csv, b.lists_csv);
    }
}

TEST_F(GlDrawOrder, WboitAndBlendMoveWithinTheirStatedBoundWhenTheDrawOrderIsReversedOnTheGpu) {
  const Extent screen{32, 24};
  const std::vector<Fragment> frags = test::draw_order_scene(screen, 4000, 6);
  const std::vector<Fragment> reversed(frags.rbegin(), frags.rend());
  for (Technique t : {Technique::Wboit, Technique::Blend}) {
    SCOPED_TRACE(to_string(t));
    const TechniqueConfig c = sized(t, screen, frags, gl::AtomicMode::Emulated64);
    const Rendered a = render(c, gl::AtomicMode::Emulated64, frags), b = render(c, gl::AtomicMode::Emulated64, reversed);
    EXPECT_EQ(a.report.counters, b.report.counters);
    EXPECT_TRUE(test::within_bound(a.image, b.image, test::reversal_bound(t, frags, screen)));
    if (t == Technique::Blend) {
      EXPECT_GT(test::largest_difference(a.image, b.image), 0.05f);
    }
  }
}

}  // namespace
}  // namespace habuffer
