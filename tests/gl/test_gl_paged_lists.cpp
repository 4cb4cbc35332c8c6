// Paged lists on the GPU path: the same lists and counters as the CPU
// container and the HA-buffer on the same stream (both paths run the same
// shared GLSL), lists beyond the private array sorted, a full pool counted
// and lossless mode regathering into a pool that holds every page, and the
// resolve's image bit for bit the HA-buffer's.
#include <gtest/gtest.h>

#include "gl_test_support.h"
#include "habuffer/lossless_build.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"

namespace habuffer {
namespace {

using test::ExactLists;

TechniqueConfig paged_config(Extent screen, gl::AtomicMode mode, std::uint32_t age_bits = 8) {
  return test::technique_config(Technique::PagedLists, screen, test::layout_of(mode), age_bits);
}

std::unique_ptr<gl::GlTechnique> gl_technique(const TechniqueConfig& c, gl::AtomicMode mode,
                                              const gl::GlBindings& bindings = {}) {
  return gl::make_gl_technique(c, OffsetSource{}, mode, bindings);
}

class GlPagedListsTest : public ::testing::Test {
 protected:
  void SetUp() override { test::gl_context(); }
};

TEST_F(GlPagedListsTest, TheGpuGivesTheCpuContainersAndTheHaBuffersListsAndCounters) {
  for (gl::AtomicMode mode : {gl::AtomicMode::Native32, gl::AtomicMode::Emulated64})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Extent screen{13 + 7 * static_cast<std::uint32_t>(seed), 9 + 2 * static_cast<std::uint32_t>(seed)};
      const StreamKind kind = seed == 2 ? StreamKind::Hot : StreamKind::Coherent;
      const std::uint32_t age_bits = seed == 3 ? 5 : 8;
      std::vector<Fragment> frags = test::stream(screen, kind, 900 + seed * 300, seed);
      frags.push_back(frags[seed]);  // an exact duplicate
      TechniqueConfig c = paged_config(screen, mode, age_bits);
      c.pool_capacity = frags.size() * kPagedListsPageNodes;
      gl::GlFrameDriver gpu(gl_technique(c, mode));
      const gl::FrameReport report = gl::ComputeInserter(gpu).insert(frags);
      PagedLists cpu(c);
      const Counters expected = cpu.insert(frags);
      const std::string what = to_string(mode) + " seed " + std::to_string(seed);
      EXPECT_EQ(report.counters, expected) << what;
      const auto back = gpu.technique().read_back();
      const ExactLists gl_lists = test::traversed_lists(*back);
      EXPECT_EQ(gl_lists, test::traversed_lists(cpu)) << what;
      EXPECT_EQ(back->count_stored(), cpu.count_stored()) << what;
      // Every page asked for is linked or lost to a race; one thread links them all.
      EXPECT_GE(report.nodes_requested, cpu.requested()) << what;
      EXPECT_EQ(report.nodes_requested % kPagedListsPageNodes, 0u) << what;
      const BuildResult ha = build(c.buffer, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
      EXPECT_EQ(gl_lists, test::traversed_lists(ha.buffer)) << what;
      EXPECT_EQ(report.counters, ha.counters) << what;
      // The read-back takes further fragments on the CPU into the GPU's pages.
      back->insert(frags);
      EXPECT_EQ(test::traversed_lists(*back), gl_lists) << what;
    }
}

TEST_F(GlPagedListsTest, ListsLongerThanThePrivateArrayAreSortedOnTheGpu) {
  const Extent screen{4, 4};
  std::vector<Fragment> frags;
  SplitMix64 rng(3);
  for (int i = 0; i < 300; ++i)
    frags.push_back({2, 1, static_cast<float>(rng.below(200)) / 211.0f, 0x40506000u + static_cast<std::uint32_t>(rng.below(2))});
  TechniqueConfig c = paged_config(screen, gl::AtomicMode::Emulated64);
  // Room for the pages the invocations racing on the one pixel allocate and lose.
  c.pool_capacity = frags.size() * kPagedListsPageNodes;
  gl::GlFrameDriver gpu(gl_technique(c, gl::AtomicMode::Emulated64));
  const gl::FrameReport r = gl::ComputeInserter(gpu).insert(frags);
  ASSERT_EQ(r.counters.failures(), 0u);
  const ExactLists expected = test::exact_lists(frags, RecordLayout(Layout::L64, 8));
  ASSERT_GT(expected.at({2, 1}).size(), HABUFFER_SORT_LOCAL);
  EXPECT_EQ(test::traversed_lists(*gpu.technique().read_back()), expected);
  EXPECT_EQ(r.counters.duplicates, frags.size() - expected.at({2, 1}).size());
}

TEST_F(GlPagedListsTest, AFullPoolIsCountedAndLosslessModeRegathersIntoAPoolThatHoldsEveryPage) {
  const Extent screen{24, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 3000, 4);
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  TechniqueConfig c = paged_config(screen, mode);
  c.pool_capacity = 1000;
  gl::GlFrameDriver lossy(gl_technique(c, mode));
  const gl::FrameReport r = gl::ComputeInserter(lossy).insert(frags);
  EXPECT_GT(r.counters.dropped_pool, 0u);
  EXPECT_EQ(r.counters.stored() + r.counters.duplicates + r.counters.dropped_pool, frags.size());
  EXPECT_EQ(r.counters.stored(), lossy.technique().read_back()->count_stored());
  EXPECT_GT(r.nodes_requested, 1000u);

  gl::GlFrameOptions options;
  options.max_attempts = 4;
  gl::GlFrameDriver lossless(gl_technique(c, mode), options);
  const gl::FrameReport l = gl::ComputeInserter(lossless).insert(frags);
  EXPECT_TRUE(l.lossless());
  ASSERT_GE(l.attempts.size(), 2u);
  EXPECT_EQ(l.attempts[0].capacity, 1000u);
  const BuildResult ha = build(c.buffer, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
  EXPECT_EQ(test::traversed_lists(*lossless.technique().read_back()), test::traversed_lists(ha.buffer));
}

TEST_F(GlPagedListsTest, TheResolveIsTheHaBuffersImageBitForBit) {
  const Extent screen{32, 24};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 5000, 8);
  const gl::AtomicMode mode = gl::AtomicMode::Emulated64;
  BufferConfig hc = test::config(screen, Extent{40, 30}, Layout::L64);
  gl::GlFrameOptions lossless;
  lossless.max_attempts = 8;
  gl::GlHaBuffer ha(hc, test::random_offsets(2), mode, lossless, test::host_bindings());
  ASSERT_TRUE(gl::ComputeInserter(ha).insert(frags).lossless());
  const glm::vec3 background(0.2f, 0.4f, 0.9f);
  TechniqueConfig c = paged_config(screen, mode);
  c.pool_capacity = 0;  // automatic: grown at once
  gl::GlFrameDriver gpu(gl_technique(c, mode, test::host_bindings()));
  EXPECT_TRUE(gl::ComputeInserter(gpu).insert(frags).lossless());
  EXPECT_EQ(test::resolve_to_image(gpu, background), test::resolve_to_image(ha, background));
}

}  // namespace
}  // namespace habuffer
