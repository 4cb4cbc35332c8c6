// The GPU path's per-fragment bookkeeping and module variants (issue 26):
// what a frame did not ask for is compiled out, and nothing the frame
// computes changes with it. Every variant of the insertion module (the
// read-first slot load, the max-age update with or without a read first, the
// slot-write tally) builds the CPU path's table bit for bit; the renderer's
// per-pixel counts, counted in the gather or by a counting pass, are the same.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <limits>

#include "gl_test_support.h"
#include "habuffer/render/scene_renderer.h"
#include "habuffer/scene_catalog.h"

namespace habuffer {
namespace {

using test::gl_context;

std::vector<gl::AtomicMode> modes() { return gl::runnable_atomic_modes(gl::query_gl_info()); }

gl::GlFrameOptions with_variant(bool slot_read_first, bool max_age_read_first, bool count_writes) {
  gl::GlFrameOptions o;
  o.module.slot_read_first = slot_read_first;
  o.module.max_age_read_first = max_age_read_first;
  o.module.count_writes = count_writes;
  return o;
}

// Every variant against the CPU path, on the cross-check streams of
// Gl.EveryAtomicModeBuildsTheCpuTableBitForBit (a NaN depth included).
TEST(GlBookkeeping, EveryModuleVariantBuildsTheCpuPathsTableAndMaxAgesBitForBit) {
  gl_context();
  struct Case {
    Extent screen, table;
    std::uint32_t age_bits;
    StreamKind kind;
    double load;
  };
  const Case cases[] = {{{32, 24}, {32, 24}, 8, StreamKind::Coherent, 0.8},
                        {{40, 30}, {57, 41}, 4, StreamKind::Random, 0.6},
                        {{64, 64}, {80, 64}, 8, StreamKind::Random, 0.9},
                        {{16, 48}, {16, 48}, 4, StreamKind::Coherent, 1.1}};
  for (gl::AtomicMode mode : modes())
    for (const gl::GlFrameOptions& o : {gl::GlFrameOptions{}, with_variant(false, false, false),
                                        with_variant(true, true, false), with_variant(false, true, true),
                                        with_variant(true, false, true)}) {
      SCOPED_TRACE(gl::to_string(mode) + " " + o.module.str());
      for (const Case& k : cases) {
        SCOPED_TRACE(k.screen.str() + " in " + k.table.str());
        const BufferConfig c = test::config(k.screen, k.table, test::layout_of(mode), k.age_bits, 8);
        auto f = test::stream(k.screen, k.kind, static_cast<std::uint64_t>(k.load * static_cast<double>(k.table.area())), 4);
        f[f.size() / 3].depth = std::numeric_limits<float>::quiet_NaN();
        gl::GlHaBuffer gpu(c, test::random_offsets(9), mode, o);
        HaBuffer cpu(c, gpu.offsets());
        const Counters want = cpu.insert(f);
        const gl::FrameReport r = gl::ComputeInserter(gpu).insert(f);
        ASSERT_EQ(want.failed_iter + r.counters.failed_iter, 0u);
        const auto table = gpu.read_table();
        for (std::uint64_t s = 0; s < cpu.slot_count(); ++s) ASSERT_EQ(table[s], cpu.slot(s)) << "slot " << s;
        EXPECT_EQ(r.counters.stored(), want.stored());
        EXPECT_EQ(r.counters.duplicates + r.counters.failed_age, want.duplicates + want.failed_age);
        if (want.failures() + r.counters.failures() == 0) {
          EXPECT_EQ(gpu.read_max_age(), cpu.max_age().ages());
          EXPECT_EQ(r.counters, want);
        }
        EXPECT_EQ(r.slot_writes.has_value(), o.module.count_writes);
        if (r.slot_writes) {
          EXPECT_GE(*r.slot_writes, want.stored());  // every record written at least once
        }
      }
    }
}

// The slot-write tally switched off changes nothing but the tally itself:
// the same table, max-age table, counters and resolved image as with it on,
// and a report that says it did not count (nullopt, not 0).
TEST(GlBookkeeping, SlotWritesSwitchedOffGiveTheSameTablesCountersAndImageAsSwitchedOn) {
  gl_context();
  const Extent screen{48, 40};
  const auto f = test::stream(screen, StreamKind::Coherent, 3000, 6);
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    const BufferConfig c = test::config(screen, {64, 56}, test::layout_of(mode), 8);
    gl::GlHaBuffer on(c, test::random_offsets(2), mode, with_variant(true, false, true));
    gl::GlHaBuffer off(c, test::random_offsets(2), mode, with_variant(true, false, false));
    const gl::FrameReport counted = gl::ComputeInserter(on).insert(f);
    const gl::FrameReport uncounted = gl::ComputeInserter(off).insert(f);
    ASSERT_EQ(counted.counters.failures(), 0u);
    ASSERT_TRUE(counted.slot_writes.has_value());
    EXPECT_GE(*counted.slot_writes, counted.counters.stored());
    EXPECT_FALSE(uncounted.slot_writes.has_value());
    EXPECT_EQ(uncounted.counters, counted.counters);
    EXPECT_EQ(off.read_table(), on.read_table());
    EXPECT_EQ(off.read_max_age(), on.read_max_age());
    EXPECT_EQ(test::resolve_to_image(off, glm::vec3(0.3f)), test::resolve_to_image(on, glm::vec3(0.3f)));
  }
}

// An unset choice of the variant is the one measured faster for the atomic
// mode and implementation (docs/performance.md, "Issue 26: GPU
// bookkeeping"); a choice made is kept.
TEST(GlBookkeeping, UnsetVariantChoicesResolveByAtomicModeAndImplementation) {
  gl_context();
  const gl::GlInfo info = gl::query_gl_info();
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    gl::GlHaBuffer gpu(test::config({8, 8}, {8, 8}, test::layout_of(mode)), test::random_offsets(1), mode);
    const gl::ModuleVariant& v = gpu.options().module;
    EXPECT_EQ(v.slot_read_first, std::optional<bool>(mode == gl::AtomicMode::Emulated64));
    EXPECT_EQ(v.max_age_read_first, std::optional<bool>(info.software_rasterizer));
    EXPECT_FALSE(v.count_writes);
    EXPECT_NE(gpu.module_source(gl::ShaderStage::Compute).find("#define HABUFFER_SLOT_READ_FIRST"), std::string::npos);
    gl::GlHaBuffer chosen(gpu.config(), test::random_offsets(1), mode, with_variant(true, false, false));
    EXPECT_EQ(chosen.options().module, with_variant(true, false, false).module);
  }
}

// The driver asks its host for the gather's call count only where the
// implementation can end calls without an outcome (llvmpipe's loop budget),
// and the renderer then counts per pixel in the gather, at no extra pass.
TEST(GlBookkeeping, TheCallCountIsAskedForOnlyWhereTheImplementationHasALoopBudget) {
  gl_context();
  const gl::GlInfo info = gl::query_gl_info();
  EXPECT_EQ(info.software_rasterizer, info.renderer.find("llvmpipe") != std::string::npos ||
                                          info.renderer.find("softpipe") != std::string::npos);
  gl::GlHaBuffer gpu(test::config({8, 8}, {8, 8}, Layout::L32), test::random_offsets(1), gl::AtomicMode::Native32);
  EXPECT_EQ(gpu.needs_call_count(), info.software_rasterizer);
  EXPECT_EQ(SceneRenderer::GatherCounts::for_driver(gpu).fragments, info.software_rasterizer);
}

struct Gathered {
  std::vector<std::uint64_t> table;
  std::vector<std::uint32_t> max_age, pixel_fragments;
  Counters counters;
  std::uint64_t rejected = 0;
  std::vector<glm::vec4> image;
};

// One frame of a scene's default view through render's renderer, counting
// `counts` in the gather, and the frame's results; then a second view
// gathered and its per-pixel counts (`second`).
Gathered gather_scene(const Scene& scene, const BufferConfig& c, gl::AtomicMode mode, const gl::GlFrameOptions& o,
                      SceneRenderer::GatherCounts counts, std::vector<std::uint32_t>& second) {
  gl::GlHaBuffer gpu(c, test::random_offsets(5), mode, o);
  SceneRenderer renderer(scene, c.screen, gpu, counts);
  const Camera camera = frame_scene(scene, {scene.default_yaw, scene.default_pitch, 45.0f}, c.screen);
  renderer.draw_opaque(camera, glm::vec3(1.0f));
  Gathered g;
  g.counters = gpu.frame([&] { renderer.gather(camera); }, [&] { return renderer.inserted(); }).counters;
  g.table = gpu.read_table();
  g.max_age = gpu.read_max_age();
  g.pixel_fragments = renderer.read_pixel_fragments();
  g.rejected = renderer.read_rejected();
  g.image = test::resolve_to_image(gpu, glm::vec3(1.0f));
  const Camera other = frame_scene(scene, {scene.default_yaw + 40.0f, scene.default_pitch, 45.0f}, c.screen);
  renderer.draw_opaque(other, glm::vec3(1.0f));
  gpu.frame([&] { renderer.gather(other); }, [&] { return renderer.inserted(); });
  second = renderer.read_pixel_fragments();
  return g;
}

// render's gather without its bookkeeping (no per-pixel counts in the
// gather, no slot-write tally) against with all of it: the same table,
// max-age table, counters, image and rejected fragments; the per-pixel
// fragment counts, which then come from a counting pass of the gathered
// view, are the same as those the gather counted, for a second view too.
TEST(GlBookkeeping, RendersGatherWithoutBookkeepingGivesTheSameTablesImageAndPerPixelCounts) {
  gl_context();
  const Scene scene = make_scene("hairball", {});
  const gl::AtomicMode mode = modes().front();
  const BufferConfig c = test::config({48, 40}, {192, 160}, test::layout_of(mode), 8);
  std::vector<std::uint32_t> second_counted, second_lazy;
  const Gathered counted = gather_scene(scene, c, mode, with_variant(true, false, true), {true, true}, second_counted);
  const Gathered lazy = gather_scene(scene, c, mode, with_variant(true, false, false), {false, false}, second_lazy);
  ASSERT_GT(counted.counters.fragments, 1000u);
  EXPECT_EQ(counted.counters.failures(), 0u);
  EXPECT_EQ(lazy.counters, counted.counters);
  EXPECT_EQ(lazy.table, counted.table);
  EXPECT_EQ(lazy.max_age, counted.max_age);
  EXPECT_EQ(lazy.image, counted.image);
  EXPECT_EQ(lazy.rejected, counted.rejected);
  EXPECT_EQ(lazy.pixel_fragments, counted.pixel_fragments);
  std::uint64_t sum = 0;
  for (std::uint32_t n : lazy.pixel_fragments) sum += n;
  EXPECT_EQ(sum, counted.counters.fragments);
  EXPECT_EQ(second_lazy, second_counted);
  EXPECT_NE(second_lazy, lazy.pixel_fragments) << "the second view must differ for the comparison to bite";
}

// A gather's per-pixel counts, when not counted in it, need the gather's
// opaque depth image: drawn over by another view, they are refused rather
// than counted against the wrong surfaces.
TEST(GlBookkeeping, UncountedPerPixelCountsAreRefusedOnceTheOpaquePassWasDrawnOver) {
  gl_context();
  const Scene scene = make_scene("quads", {});
  const gl::AtomicMode mode = modes().front();
  const BufferConfig c = test::config({24, 24}, {32, 32}, test::layout_of(mode), 8);
  gl::GlHaBuffer gpu(c, test::random_offsets(5), mode);
  SceneRenderer renderer(scene, c.screen, gpu, {false, false});
  const Camera a = frame_scene(scene, {scene.default_yaw, scene.default_pitch, 45.0f}, c.screen);
  const Camera b = frame_scene(scene, {scene.default_yaw + 90.0f, scene.default_pitch, 45.0f}, c.screen);
  renderer.draw_opaque(a, glm::vec3(1.0f));
  gpu.frame([&] { renderer.gather(a); });
  renderer.draw_opaque(b, glm::vec3(1.0f));
  EXPECT_THROW((void)renderer.read_pixel_fragments(), std::logic_error);
  EXPECT_TRUE(renderer.read_pixel_culled().empty()) << "culled counts were not asked for";
}

}  // namespace
}  // namespace habuffer
