// The peers on the GPU path (sorted lists, the k-buffer with and without its
// occupancy map, early termination and saturation depth): the same lists
// and counters as their CPU builds on the same stream, in every atomic mode
// llvmpipe runs, and the exact ones resolve the HA-buffer's image; the
// blended baselines (wboit, blend) give the CPU's images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gl_test_support.h"
#include "habuffer/lossless_build.h"

namespace habuffer {
namespace {

using test::ExactLists;

TechniqueConfig peer_config(Technique t, Extent screen, gl::AtomicMode mode) {
  return test::technique_config(t, screen, test::layout_of(mode));
}

class GlPeers : public ::testing::Test {
 protected:
  void SetUp() override { test::gl_context(); }
  static std::vector<gl::AtomicMode> modes() { return {gl::AtomicMode::Native32, gl::AtomicMode::Emulated64}; }
};

// GL against CPU on the same stream: counters and lists.
void expect_same_as_cpu(const TechniqueConfig& c, gl::AtomicMode mode, const std::vector<Fragment>& frags,
                        const std::string& what) {
  gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, mode, test::host_bindings()));
  const gl::FrameReport report = gl::ComputeInserter(gpu).insert(frags);
  const auto cpu = make_fragment_buffer(c, OffsetSource{});
  const Counters expected = cpu->insert(frags);
  EXPECT_EQ(report.counters, expected) << what;
  EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), test::traversed_lists(*cpu)) << what;
}

TEST_F(GlPeers, SortedListsAndTheKBufferGiveTheCpuListsAndCountersInEveryMode) {
  for (gl::AtomicMode mode : modes())
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const Extent screen{23 + 5 * static_cast<std::uint32_t>(seed), 15};
      const std::vector<Fragment> frags =
          test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 2500 + 500 * seed, seed);
      const std::string at = to_string(mode) + " seed " + std::to_string(seed);
      TechniqueConfig s = peer_config(Technique::SortedLists, screen, mode);
      s.pool_capacity = frags.size();
      expect_same_as_cpu(s, mode, frags, "sorted-lists " + at);
      for (std::uint32_t k : {1u, 4u})
        for (bool occupancy : {false, true}) {
          TechniqueConfig kb = peer_config(Technique::KBuffer, screen, mode);
          kb.layers = k;
          kb.occupancy = occupancy;
          kb.occupancy_words = 2;
          expect_same_as_cpu(kb, mode, frags, "kbuffer k " + std::to_string(k) + " occupancy " +
                                                   std::to_string(occupancy) + " " + at);
        }
    }
}

TEST_F(GlPeers, SortedListsWithoutCullEqualTheHaBufferAndResolveItsImageBitForBit) {
  const Extent screen{32, 24};
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 5000, 8);
  gl::GlFrameOptions lossless;
  lossless.max_attempts = 8;
  gl::GlHaBuffer ha(test::config(screen, Extent{40, 30}, Layout::L64), test::random_offsets(2), mode, lossless,
                    test::host_bindings());
  ASSERT_TRUE(gl::ComputeInserter(ha).insert(frags).lossless());
  const glm::vec3 background(0.2f, 0.4f, 0.9f);
  TechniqueConfig c = peer_config(Technique::SortedLists, screen, mode);
  c.pool_capacity = frags.size();
  gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, mode, test::host_bindings()));
  gl::ComputeInserter(gpu).insert(frags);
  EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), test::traversed_lists(*ha.technique().read_back()));
  EXPECT_EQ(test::resolve_to_image(gpu, background), test::resolve_to_image(ha, background));
}

// Early termination and saturation on the GPU, on planes inserted front to
// back: every pixel keeps at least the planes in front of opacity tau (7 at
// alpha 128/255 and tau 0.99), the rest is culled or, with saturation, also
// rejected before insertion; nothing fails.
TEST_F(GlPeers, EarlyTerminationAndSaturationCountAsTheCpuOnOrderedPlanes) {
  const Extent screen{16, 8};
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  std::vector<Fragment> planes;
  for (std::uint32_t k = 0; k < 24; ++k)
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x)
        planes.push_back({x, y, 0.1f + 0.03f * static_cast<float>(k), ((30u + 8u * k) << 24) | 0x60A000u | 128u});
  for (Technique t : {Technique::SortedLists, Technique::Ha})
    for (bool saturation : {false, true}) {
      TechniqueConfig c = peer_config(t, screen, mode);
      c.buffer.table = {48, 48};
      c.buffer.early_cull_tau = 0.99f;
      c.buffer.saturation = saturation;
      c.pool_capacity = planes.size();
      // Each plane its own chunk, in order (one fragment per pixel): a
      // pixel's calls never run at once, whatever the GPU's width (one
      // running every plane at once would see no plane in front of
      // another). Sorted lists are per pixel, so they count as the CPU
      // does serially. The HA-buffer's records of other pixels still move
      // concurrently within a chunk (evictions), and an evicted record meets
      // a saturation depth set meanwhile or not: the H100 stored 895 where
      // the CPU stores 896. Its counts are held within 1 %.
      std::vector<std::size_t> ends;
      for (std::size_t k = 1; k <= 24; ++k) ends.push_back(k * screen.area());
      // Emulated64 cuts a call short after lock_spin_limit busy locks and
      // resumes it after the gather, out of order: a generous limit keeps
      // every call in its chunk.
      gl::GlFrameOptions o;
      o.lock_spin_limit = 1u << 20;
      gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, mode, test::host_bindings()), o);
      const gl::FrameReport r = gl::ComputeInserter(gpu).insert(planes, ends);
      const Counters expected = make_fragment_buffer(c, OffsetSource{})->insert(planes);
      const std::string what = to_string(t) + " saturation " + std::to_string(saturation);
      if (t == Technique::SortedLists) {  // 32-bit compare-and-swap: never cut short, never deferred
        EXPECT_EQ(r.deferred, 0u) << what;
        EXPECT_EQ(r.counters, expected) << what;
      }
      const double stored = static_cast<double>(r.counters.stored()), want = static_cast<double>(expected.stored());
      EXPECT_NEAR(stored, want, want / 100.0) << what;
      EXPECT_EQ(r.counters.fragments, expected.fragments) << what;
      EXPECT_EQ(r.counters.failures(), 0u) << what;
      EXPECT_GE(expected.stored(), 7 * screen.area()) << what;
      EXPECT_GT(r.counters.culled + r.counters.saturated_rejected, 0u);
      if (!saturation) {
        EXPECT_EQ(r.counters.saturated_rejected, 0u) << to_string(t);
      }
    }
}

// wboit and blend on the GPU: the stream drawn as points in stream order
// through the fixed-function blender gives the CPU's counters exactly and
// its accumulators (read back) and resolved image within float rounding
// (the blender may fuse or reorder its multiply-adds); invalid depths count
// invalid and blend nothing; a second frame starts from cleared accumulators.
TEST_F(GlPeers, WboitAndBlendOnTheGpuGiveTheCpuImagesAndCountersInStreamOrder) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const Extent screen{19 + 4 * static_cast<std::uint32_t>(seed), 13};
    std::vector<Fragment> frags = test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 3000, seed);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (float bad : {nan, 1.5f, -0.25f}) frags.push_back({3, 2, bad, 0xFF8040C0u});
    const std::vector<glm::vec3> backgrounds(screen.area(), glm::vec3(0.2f, 0.3f, 0.4f));
    for (Technique t : {Technique::Wboit, Technique::Blend}) {
      TechniqueConfig c = peer_config(t, screen, gl::AtomicMode::Emulated64);
      c.depth_range = {0.05f, 0.95f};
      gl::GlFrameDriver gpu(gl::make_gl_technique(c, OffsetSource{}, gl::AtomicMode::Emulated64, test::host_bindings()));
      gl::ComputeInserter inserter(gpu);
      const auto cpu = make_fragment_buffer(c, OffsetSource{});
      const Counters expected = cpu->insert(frags);
      const std::string what = to_string(t) + " seed " + std::to_string(seed);
      for (int frame = 0; frame < 2; ++frame) {
        const gl::FrameReport report = inserter.insert(frags);
        EXPECT_EQ(report.counters, expected) << what;
        EXPECT_EQ(report.counters.invalid, 3u) << what;
        EXPECT_EQ(report.counters.blended, frags.size() - 3) << what;
        const std::vector<glm::vec4> want = cpu->composite_image(backgrounds);
        EXPECT_LT(test::largest_difference(gpu.technique().read_back()->composite_image(backgrounds), want), 2e-5f) << what;
        EXPECT_LT(test::largest_difference(test::resolve_to_image(gpu, backgrounds[0]), want), 2e-5f) << what;
      }
    }
  }
}

}  // namespace
}  // namespace habuffer
