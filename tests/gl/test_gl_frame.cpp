// The GPU path's per-frame machinery (SPEC 8): the clear pass's occlusion
// count, adaptive sizing with one frame of latency, lossless regathering.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <chrono>

#include "gl_test_support.h"
#include "habuffer/lossless_build.h"
#include "habuffer/render/stream_build.h"

#include <stdexcept>

namespace habuffer {
namespace {

using test::gl_context;

std::vector<gl::AtomicMode> modes() { return gl::runnable_atomic_modes(gl::query_gl_info()); }

// The occlusion query over the clear pass counts exactly the stored records,
// also when the pass runs in tiles (here forced by a small tile side), and
// the pass leaves every slot empty. The count of a frame's clear pass is read
// from the query buffer at the next frame's start.
TEST(GlFrame, ClearPassOcclusionCountIsExactAndEmptiesTheTable) {
  gl_context();
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    for (std::uint32_t tile : {0u, 7u, 64u}) {
      SCOPED_TRACE("tile " + std::to_string(tile));
      const BufferConfig c = test::config({50, 30}, {71, 43}, test::layout_of(mode), 8);
      gl::GlFrameOptions o;
      o.clear_tile = tile;
      gl::GlHaBuffer gpu(c, test::random_offsets(4), mode, o);
      gl::ComputeInserter inserter(gpu);
      const auto f = test::stream(c.screen, StreamKind::Coherent, 2400, tile + 1);
      const gl::FrameReport first = inserter.insert(f);
      EXPECT_FALSE(first.cleared);
      EXPECT_FALSE(first.counted_stored.has_value());
      const std::uint64_t exact = test::cpu_twin(gpu, f).count_stored();
      ASSERT_GT(exact, 1000u);
      EXPECT_EQ(first.counters.stored(), exact);
      EXPECT_EQ(gpu.count_stored(), exact);  // counting only: the table stays
      EXPECT_EQ(gpu.count_stored(), exact);
      const auto t0 = std::chrono::steady_clock::now();
      const gl::FrameReport empty = gpu.frame([] {});
      const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      // Pass clocks: positive and within the frame's wall-clock time.
      EXPECT_GT(empty.clear.wall_ms, 0.0);
      EXPECT_GT(empty.reset.wall_ms, 0.0);
      EXPECT_LE(empty.clear.wall_ms + empty.reset.wall_ms + empty.gather.wall_ms, wall_ms);
      EXPECT_GE(empty.clear.gpu_ms, 0.0);
      EXPECT_TRUE(empty.cleared);
      EXPECT_FALSE(empty.counted_stored.has_value()) << "the count is read one frame later";
      EXPECT_EQ(empty.counters.fragments, 0u);
      const auto table = gpu.read_table();
      EXPECT_EQ(std::count(table.begin(), table.end(), 0u), static_cast<std::ptrdiff_t>(table.size()));
      EXPECT_EQ(gpu.count_stored(), 0u);
      const gl::FrameReport third = gpu.frame([] {});
      ASSERT_TRUE(third.counted_stored.has_value());
      EXPECT_EQ(*third.counted_stored, exact);
      EXPECT_EQ(third.counted_table, c.table);
    }
  }
}

// A scripted sequence whose content grows then shrinks: frame k's table is
// ResizePolicy::next of frame k-1's table and the records it asked to keep
// (its outcome counters, read with the frame: Readback::Immediate), a frame
// that still overflows regathers into the table for its own count; never
// below the screen, offsets regenerated for every size, and each frame's
// table is the CPU path's.
TEST(GlFrame, AdaptiveSizingDecidesFromTheLastFramesCountAndRegathersByTheCount) {
  gl_context();
  const Extent screen{40, 32};
  const std::vector<std::uint64_t> script{400, 800, 1000, 1100, 1100, 1200, 3000, 1200, 700, 300, 200, 100, 100, 100, 100};
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    gl::GlFrameOptions o;
    o.adaptive = true;
    gl::GlHaBuffer gpu(test::config(screen, {}, test::layout_of(mode), 8), test::random_offsets(6), mode, o);
    gl::ComputeInserter inserter(gpu);
    Extent previous_table;
    std::uint64_t previous_records = 0;
    bool grew = false, shrank = false;
    for (std::size_t k = 0; k < script.size(); ++k) {
      SCOPED_TRACE("frame " + std::to_string(k));
      const auto f = test::stream(screen, StreamKind::Random, script[k], 100 + k);
      const gl::FrameReport r = inserter.insert(f);
      ASSERT_FALSE(r.attempts.empty());
      EXPECT_TRUE(r.lossless());
      if (k == 0) {
        EXPECT_FALSE(r.sized_by.has_value());
      } else {
        ASSERT_TRUE(r.sized_by.has_value());
        EXPECT_EQ(r.sized_by->frame, k - 1);
        EXPECT_EQ(r.sized_by->records, previous_records);
        const Extent next = o.policy.next(previous_table, screen, previous_records);
        EXPECT_EQ(r.attempts.front().table, next);
        EXPECT_EQ(r.resized, next != previous_table);
        grew |= next.area() > previous_table.area();
        shrank |= next.area() < previous_table.area();
      }
      for (std::size_t a = 1; a < r.attempts.size(); ++a) {
        const std::uint64_t counted = r.attempts[a - 1].counters.records_needed();
        EXPECT_EQ(r.attempts[a].sized_for, counted);
        EXPECT_EQ(r.attempts[a].table, o.policy.grown(r.attempts[a - 1].table, screen, counted));
      }
      EXPECT_LE(r.attempts.size(), 2u) << "any jump in one regather";
      EXPECT_GE(r.table.x, screen.x);
      EXPECT_GE(r.table.y, screen.y);
      EXPECT_EQ(gpu.offsets().table(), r.table);
      const HaBuffer cpu = test::cpu_twin(gpu, f);
      EXPECT_EQ(gpu.read_table(), test::table_words(cpu));
      previous_table = r.table;
      previous_records = r.counters.records_needed();
      EXPECT_EQ(previous_records, cpu.count_stored());
    }
    EXPECT_TRUE(grew);
    EXPECT_TRUE(shrank);
    EXPECT_EQ(previous_table, screen);  // shrank back to the geometry rule, not below
  }
}

// Lossless mode: a frame that fails is gathered again into grown tables,
// exactly as the CPU path's lossless build does, and loses nothing.
TEST(GlFrame, LosslessModeRegathersIntoTheCpuPathsTablesAndLosesNothing) {
  gl_context();
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config({32, 32}, {32, 32}, test::layout_of(mode), 4);  // AMAX 15
    StreamOptions so;
    so.kind = StreamKind::Random;
    so.count = 1200;  // more fragments than slots: the screen-sized table must fail
    so.seed = 8;
    const auto f = make_stream(c.screen, so);
    gl::GlFrameOptions o;
    o.max_attempts = 12;
    gl::GlHaBuffer gpu(c, test::random_offsets(2), mode, o);
    const gl::FrameReport r = gl::ComputeInserter(gpu).insert(f);
    const BuildResult cpu = build(c, test::random_offsets(2), f, {}, o.policy, *o.max_attempts);
    ASSERT_GT(r.attempts.size(), 1u) << "the stream should fail in the first table";
    EXPECT_GT(r.attempts.front().counters.failures(), 0u);
    EXPECT_TRUE(r.lossless());
    ASSERT_EQ(r.attempts.size(), cpu.attempts.size());
    for (std::size_t i = 0; i < r.attempts.size(); ++i) EXPECT_EQ(r.attempts[i].table, cpu.attempts[i].table);
    EXPECT_EQ(r.table, cpu.buffer.table());
    EXPECT_EQ(gpu.read_table(), test::table_words(cpu.buffer));
    EXPECT_EQ(gpu.read_max_age(), cpu.buffer.max_age().ages());
    EXPECT_EQ(r.counters, cpu.counters);
  }
}

// Lossless mode's one rule (lossless_attempts) on both paths: a pixel deeper
// than AMAX, which no table holds, stops the GPU's builder after its first
// attempt as it stops the CPU's, naming the same pixel and the same failure.
TEST(GlFrame, TheGpuBuilderStopsGrowingForAPixelDeeperThanAmaxAsTheCpuBuilderDoes) {
  gl_context();
  std::vector<Fragment> f;
  for (int i = 0; i < 20; ++i) f.push_back({1, 0, (static_cast<float>(i) + 0.5f) / 20.0f, 0xff});  // AMAX 15
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 4; ++x) f.push_back({x, y, 0.125f, 0x80});
  for (const Layout layout : {Layout::L32, Layout::L64}) {
    if (!gl::chosen_atomic_mode(gl::query_gl_info(), layout)) continue;
    SCOPED_TRACE(layout == Layout::L32 ? "L32" : "L64");
    const TechniqueConfig c = ha_technique_config(test::config({4, 4}, {4, 4}, layout, 4));
    const TechniqueBuild cpu = build_technique(c, test::random_offsets(2), f, {}, ResizePolicy{}, 8);
    const TechniqueBuild gpu = build_technique_on_gl(c, test::random_offsets(2), f, ResizePolicy{}, 8);
    EXPECT_EQ(cpu.attempts.size(), 1u);
    EXPECT_EQ(gpu.attempts.size(), 1u) << "no growth for a pixel no table holds";
    ASSERT_TRUE(cpu.too_deep.has_value());
    ASSERT_TRUE(gpu.too_deep.has_value());
    EXPECT_EQ(gpu.too_deep->pixel, glm::uvec2(1, 0));
    EXPECT_EQ(gpu.too_deep->pixel, cpu.too_deep->pixel);
    EXPECT_EQ(gpu.too_deep->records, cpu.too_deep->records);
    EXPECT_FALSE(gpu.lossless());
    const std::string reason = lossless_failure_reason(gpu, f, 8);
    EXPECT_EQ(reason, lossless_failure_reason(cpu, f, 8));
    EXPECT_NE(reason.find("more attempts cannot help (--max-attempts 8)"), std::string::npos) << reason;
  }
}

// A gather that throws halfway leaves no query active and the records it
// inserted are still counted and cleared by the next frame.
TEST(GlFrame, AGatherThatThrowsLeavesNoQueryOpenAndIsClearedNextFrame) {
  gl_context();
  const gl::AtomicMode mode = modes().front();
  const BufferConfig c = test::config({32, 32}, {40, 40}, test::layout_of(mode), 8);
  gl::GlHaBuffer gpu(c, test::random_offsets(3), mode);
  gl::ComputeInserter inserter(gpu);
  const auto f = test::stream(c.screen, StreamKind::Random, 600, 5);
  inserter.upload(f);
  while (glGetError() != GL_NO_ERROR) {
  }
  EXPECT_THROW(gpu.frame([&] {
    inserter.dispatch();
    throw std::runtime_error("host gather failed");
  }),
               std::runtime_error);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const std::uint64_t exact = test::cpu_twin(gpu, f).count_stored();
  const gl::FrameReport next = gpu.frame([] {});
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_TRUE(next.cleared);
  EXPECT_EQ(gpu.count_stored(), 0u);
  const gl::FrameReport after = gpu.frame([] {});
  ASSERT_TRUE(after.counted_stored.has_value());
  EXPECT_EQ(*after.counted_stored, exact);
}

// Lossless mode tells lock contention from a full table: give-ups of the
// emulated atomic left unresumed (no resume rounds) are gathered again into
// the same table, never a larger one.
TEST(GlFrame, LosslessModeRetriesLockGiveUpsWithoutGrowingTheTable) {
  gl_context();
  const auto all = modes();
  if (std::find(all.begin(), all.end(), gl::AtomicMode::Emulated64) == all.end()) GTEST_SKIP() << "no emulated64";
  const BufferConfig c = test::config({16, 16}, {32, 32}, Layout::L64, 8);
  std::vector<Fragment> f;
  for (std::uint32_t i = 0; i < 2048; ++i)  // neighbours share a pixel: they contend
    f.push_back({(i / 16) % 16, 3, static_cast<float>(i % 16 + 1) / 32.0f, 0x80808000u + i % 16});
  gl::GlFrameOptions o;
  o.lock_spin_limit = 1;
  o.resume_rounds = 0;
  o.cut_short_retries = 0;
  o.max_attempts = 4;
  gl::GlHaBuffer gpu(c, test::random_offsets(3), gl::AtomicMode::Emulated64, o);
  const gl::FrameReport r = gl::ComputeInserter(gpu).insert(f);
  ASSERT_GT(r.attempts.front().counters.failed_iter, 0u);
  EXPECT_GT(r.attempts.size(), 1u);
  for (const BuildAttempt& a : r.attempts) EXPECT_EQ(a.table, c.table);
  EXPECT_EQ(r.table, c.table);
  EXPECT_EQ(r.counters.failed_iter, r.cut_short);
  EXPECT_EQ(r.counters.failed_age, 0u);
}

}  // namespace
}  // namespace habuffer
