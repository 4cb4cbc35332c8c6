// The Vulkan path (issue 48) on the machine's Vulkan device (lavapipe here,
// with the Khronos validation layer watching: a validation message fails the
// call that caused it). The HA-buffer's builds from the GL tests' fixtures
// (gpu_fixtures.h), bit for bit with the CPU path.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gpu_fixtures.h"
#include "habuffer/lossless_build.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/vk.h"
#include "test_support.h"
#include "vk_test_support.h"

namespace habuffer {
namespace {

TEST(Vulkan, AHeadlessDeviceIsChosenWithTheFeaturesTheLibraryReads) {
  REQUIRE_VULKAN();
  const vk::VulkanInfo& info = context().info();
  EXPECT_FALSE(info.name.empty());
  EXPECT_GE(info.api, VK_API_VERSION_1_2);
  EXPECT_TRUE(info.fragment_stores);
  EXPECT_GT(info.max_storage_range, 0u);
  const auto modes = vk::runnable_atomic_modes(info);
  ASSERT_FALSE(modes.empty());
  EXPECT_EQ(modes.front(), AtomicMode::Native32);
  // lavapipe has 64-bit buffer atomics: the paper's L64 record runs native64
  // here, which the GL path on llvmpipe can only emulate.
  if (info.software && info.buffer_int64_atomics) {
    EXPECT_EQ(vk::chosen_atomic_mode(info, Layout::L64), AtomicMode::Native64);
  }
}

TEST(Vulkan, ADeviceChoiceThatMatchesNoneIsRefusedNamingTheDevicesThereAre) {
  REQUIRE_VULKAN();
  vk::ContextOptions by_index;
  by_index.device.index = 97;
  by_index.validation = false;
  const std::string e1 = error_of([&] { vk::VulkanContext c(by_index); });
  EXPECT_NE(e1.find("device 97"), std::string::npos) << e1;
  EXPECT_NE(e1.find("0: "), std::string::npos) << e1;
  vk::ContextOptions by_name;
  by_name.device.name = "no such device anywhere";
  by_name.validation = false;
  const std::string e2 = error_of([&] { vk::VulkanContext c(by_name); });
  EXPECT_NE(e2.find("matches none"), std::string::npos) << e2;
  // A part of the first device's name, in another case, finds it.
  vk::ContextOptions found;
  const std::string name = vk::list_devices().front().name;
  found.device.name = name.substr(0, 4);
  for (char& ch : found.device.name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  found.validation = false;
  EXPECT_EQ(vk::VulkanContext(found).info().name.substr(0, 4), name.substr(0, 4));
}

TEST(Vulkan, EnvironmentSettingsAreReadOrRefusedInOneLine) {
  {
    const ScopedEnv validation("HABUFFER_VK_VALIDATION", "yes");
    const std::string e = error_of([] { (void)vk::ContextOptions::validation_from_environment(); });
    EXPECT_NE(e.find("HABUFFER_VK_VALIDATION='yes' is not 0 or 1"), std::string::npos) << e;
  }
  {
    const ScopedEnv device("HABUFFER_VK_DEVICE", "3");
    EXPECT_EQ(vk::DeviceChoice::from_environment().index, 3u);
  }
  {
    const ScopedEnv device("HABUFFER_VK_DEVICE", "llvmpipe");
    EXPECT_EQ(vk::DeviceChoice::from_environment().name, "llvmpipe");
  }
  const ScopedEnv device("HABUFFER_VK_DEVICE", nullptr);
  EXPECT_EQ(vk::DeviceChoice::from_environment().str(), "the first usable device");
}

TEST(Vulkan, AValidationMessageFailsTheSubmissionThatCausedIt) {
  REQUIRE_VULKAN();
  if (!context().validation()) GTEST_SKIP() << "the validation layer is off (HABUFFER_VK_VALIDATION, or not installed)";
  const vk::VulkanBuffer buffer(context(), 64);
  // A fill at an offset that is not a multiple of 4 breaks a valid-usage rule.
  const std::string e = error_of([&] {
    context().submit_and_wait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 2, 8, 0u); },
                              "a bad fill");
  });
  EXPECT_NE(e.find("a bad fill: validation error"), std::string::npos) << e;
  // Refused before the submission: the driver never saw the bad command.
  // The messages were taken: the next submission is clean.
  context().submit_and_wait([&](VkCommandBuffer cmd) { buffer.record_zero(cmd); }, "a good fill");
}

TEST(Vulkan, SharedGlslCompilesToSpirvForEveryTechniqueInTheRunnableModes) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info()))
    for (Technique t : all_techniques()) {
      if (!stores_lists(t)) continue;  // the blended baselines' entry draws points (not on Vulkan yet)
      SCOPED_TRACE(to_string(t) + " " + to_string(mode));
      const auto spirv = vk::compile_to_spirv(vk::vulkan_insert_stream_compute(t, mode), vk::SpirvStage::Compute,
                                              to_string(t) + " insert");
      ASSERT_GT(spirv.size(), 5u);
      EXPECT_EQ(spirv[0], 0x07230203u);  // SPIR-V's magic number
    }
  const std::string e = error_of([] {
    (void)vk::compile_to_spirv("#version 450\nvoid main() { undeclared_name = 1; }\n", vk::SpirvStage::Compute, "bad");
  });
  EXPECT_NE(e.find("bad does not compile for Vulkan"), std::string::npos) << e;
  EXPECT_NE(e.find("undeclared_name"), std::string::npos) << e;
}

TEST(Vulkan, EveryRunnableModeBuildsTheCpuTableBitForBit) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());  // each mode run, not the chosen one
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    SCOPED_TRACE(to_string(mode));
    for (const test::TableCase& k : test::gpu_table_cases()) {  // the GL test's cases
      SCOPED_TRACE(k.screen.str() + " in " + k.table.str());
      TechniqueConfig c;
      c.technique = Technique::Ha;
      c.buffer = test::config(k.screen, k.table, layout, k.age_bits, 8);
      auto f = test::stream(k.screen, k.kind, static_cast<std::uint64_t>(k.load * static_cast<double>(k.table.area())), 4);
      f[f.size() / 3].depth = std::numeric_limits<float>::quiet_NaN();
      const OffsetSource offsets = test::seeded_random_offsets(9);
      vk::VulkanBuildInfo info;
      const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, offsets, f, {}, 1, &info);
      EXPECT_EQ(info.atomic_mode, to_string(mode));
      EXPECT_EQ(info.ended_by_driver, 0u);  // every call ended with an outcome
      HaBuffer cpu(c.buffer, offsets.make(c.buffer.table, c.buffer.record_layout().max_age()));
      const Counters nc = cpu.insert(f);
      const auto* table = dynamic_cast<const HaBuffer*>(gpu.buffer.get());
      ASSERT_NE(table, nullptr);
      for (std::uint64_t s = 0; s < cpu.slot_count(); ++s) ASSERT_EQ(table->slot(s), cpu.slot(s)) << "slot " << s;
      EXPECT_EQ(table->max_age().ages(), cpu.max_age().ages());
      EXPECT_EQ(gpu.counters.stored(), nc.stored());
      EXPECT_EQ(gpu.counters.invalid, nc.invalid);
      EXPECT_EQ(gpu.counters.fragments, nc.fragments);
      if (nc.failures() + gpu.counters.failures() == 0) {
        EXPECT_EQ(gpu.counters, nc);
      }
      // The comparison bites: other offsets give another table.
      const TechniqueBuild other = vk::build_technique_on_vulkan(context(), c, test::seeded_random_offsets(10), f);
      bool differs = false;
      for (std::uint64_t s = 0; s < cpu.slot_count() && !differs; ++s)
        differs = dynamic_cast<const HaBuffer&>(*other.buffer).slot(s) != cpu.slot(s);
      EXPECT_TRUE(differs);
    }
  }
}

TEST(Vulkan, LosslessModeGrowsTheTableAsTheCpuDoesAndEndsWithItsLists) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
    if (mode == AtomicMode::Native32) continue;  // the test's records are L64
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());
    for (std::uint64_t seed : {3u, 4u}) {
      SCOPED_TRACE(to_string(mode) + " seed " + std::to_string(seed));
      TechniqueConfig c;
      c.technique = Technique::Ha;
      c.buffer = test::config({48, 40}, {48, 40});
      const auto f = test::stream(c.buffer.screen, StreamKind::Coherent, 48 * 40 * 2, seed);  // twice the table
      const OffsetSource offsets = test::seeded_random_offsets(seed);
      const TechniqueBuild cpu = build_technique(c, offsets, f, {}, {}, 6);
      const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, offsets, f, {}, 6);
      ASSERT_TRUE(cpu.lossless());
      ASSERT_TRUE(gpu.lossless());
      ASSERT_EQ(gpu.attempts.size(), cpu.attempts.size());
      EXPECT_GT(gpu.attempts.size(), 1u);
      for (std::size_t a = 0; a < cpu.attempts.size(); ++a) {
        EXPECT_EQ(gpu.attempts[a].table, cpu.attempts[a].table) << "attempt " << a;
        EXPECT_EQ(gpu.attempts[a].counters.stored(), cpu.attempts[a].counters.stored()) << "attempt " << a;
      }
      EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
    }
  }
}

// The linked lists (sorted after the gather)
// from the GL tests' streams: an automatic pool that
// grows as the CPU's does, the sort pass, the lists equal the CPU's; a pool too small, lossy, drops
// as many as the CPU and holds what it counts.
TEST(Vulkan, LinkedListsBuildTheCpuListsWithTheirPoolsGrownAlike) {
  REQUIRE_VULKAN();
  for (Technique t : {Technique::Lists})
    for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
      const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());  // each mode run, not the chosen one
      const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
      SCOPED_TRACE(to_string(t) + " " + to_string(mode));
      for (const test::TableCase& k : test::gpu_table_cases()) {
        SCOPED_TRACE(k.screen.str());
        TechniqueConfig c = test::technique_config(t, k.screen, layout, k.age_bits);
        const auto f = test::draw_order_scene(k.screen, static_cast<std::size_t>(k.load * static_cast<double>(k.screen.area()) * 2), 5);
        const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 4);  // the automatic pool
        const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, f, {}, 4);
        ASSERT_EQ(gpu.attempts.size(), cpu.attempts.size());
        // Lossless mode from a pool of a tenth of the fragments: the pool
        // grows by the nodes the gather asked for, as on the CPU.
        TechniqueConfig small = c;
        small.pool_capacity = std::max<std::uint64_t>(f.size() / 10, 1);
        const TechniqueBuild grown_cpu = build_technique(small, {}, f, {}, {}, 4);
        const TechniqueBuild grown_gpu = vk::build_technique_on_vulkan(context(), small, {}, f, {}, 4);
        ASSERT_EQ(grown_gpu.attempts.size(), grown_cpu.attempts.size());
        EXPECT_GT(grown_gpu.attempts.size(), 1u);
        for (std::size_t a = 0; a < grown_cpu.attempts.size(); ++a)
          EXPECT_EQ(grown_gpu.attempts[a].capacity, grown_cpu.attempts[a].capacity) << "attempt " << a;
        EXPECT_TRUE(grown_gpu.lossless());
        EXPECT_EQ(test::traversed_lists(*grown_gpu.buffer), test::traversed_lists(*grown_cpu.buffer));
        for (std::size_t a = 0; a < cpu.attempts.size(); ++a)
          EXPECT_EQ(gpu.attempts[a].capacity, cpu.attempts[a].capacity) << "attempt " << a;
        EXPECT_EQ(gpu.counters, cpu.counters);
        EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
        // A fixed pool of a third of the fragments: lossy, as many drops as
        // on the CPU (which fragments drop depends on arrival order, so the
        // merges may differ), and the lists hold what the counters say.
        c.pool_capacity = f.size() / 3;
        const TechniqueBuild small_cpu = build_technique(c, {}, f, {}, {}, 1);
        const TechniqueBuild small_gpu = vk::build_technique_on_vulkan(context(), c, {}, f);
        EXPECT_GT(small_gpu.counters.dropped_pool, 0u);
        EXPECT_EQ(small_gpu.counters.dropped_pool, small_cpu.counters.dropped_pool);
        std::uint64_t held = 0;
        for (const auto& [pixel, entries] : test::traversed_lists(*small_gpu.buffer)) held += entries.size();
        EXPECT_EQ(held, small_gpu.counters.stored());
      }
    }
}

// Sorted lists (a compare-and-swap retry loop) as GlPeers checks them on
// GL: on coherent and hot streams, with a pool for every fragment, the CPU's
// counters and lists in every runnable mode; from an automatic pool, lossless
// mode ends with the CPU's lists (how many nodes an attempt asks for depends
// on the arrival order: a duplicate takes none when its twin is linked
// first); with early termination on planes inserted front to back, one
// plane a build, every pixel keeps the planes in front of tau and the CPU's
// counts.
TEST(Vulkan, SortedListsGiveTheCpuListsAndCountersInEveryRunnableMode) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());  // each mode run, not the chosen one
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Extent screen{23 + 5 * static_cast<std::uint32_t>(seed), 15 + static_cast<std::uint32_t>(seed)};
      const std::vector<Fragment> f =
          test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 2500 + 900 * seed, seed);
      SCOPED_TRACE(to_string(mode) + " seed " + std::to_string(seed));
      TechniqueConfig c = test::technique_config(Technique::SortedLists, screen, layout);
      c.pool_capacity = f.size();
      const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 1);
      const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, f);
      EXPECT_EQ(gpu.counters, cpu.counters);
      EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
      TechniqueConfig automatic = c;
      automatic.pool_capacity = 0;
      const TechniqueBuild grown = vk::build_technique_on_vulkan(context(), automatic, {}, f, {}, 6);
      EXPECT_TRUE(grown.lossless());
      EXPECT_EQ(test::traversed_lists(*grown.buffer), test::traversed_lists(*cpu.buffer));
    }
    if (layout != Layout::L64) continue;  // early termination reads opacity from the colour
    const Extent screen{16, 8};
    TechniqueConfig c = test::technique_config(Technique::SortedLists, screen, layout);
    c.buffer.early_cull_tau = 0.99f;
    c.pool_capacity = 24 * screen.area();
    std::vector<Fragment> planes;
    for (std::uint32_t k = 0; k < 24; ++k)
      for (std::uint32_t y = 0; y < screen.y; ++y)
        for (std::uint32_t x = 0; x < screen.x; ++x)
          planes.push_back({x, y, 0.1f + 0.03f * static_cast<float>(k), ((30u + 8u * k) << 24) | 0x60A000u | 128u});
    const TechniqueBuild cpu = build_technique(c, {}, planes, {}, {}, 1);
    EXPECT_GT(cpu.counters.culled, 0u);
    // One plane per invocation of a pixel: the whole stream in one dispatch
    // runs a pixel's planes at once, so which are culled depends on timing;
    // sorted by depth, every pixel keeps the planes in front of tau.
    const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, planes);
    EXPECT_EQ(gpu.counters.fragments, cpu.counters.fragments);
    EXPECT_EQ(gpu.counters.failures(), 0u);
    EXPECT_GE(gpu.counters.stored(), cpu.counters.stored());
    for (const auto& [pixel, entries] : test::traversed_lists(*gpu.buffer)) EXPECT_GE(entries.size(), 7u);
  }
}

// The k-buffer as GlPeers checks it on GL: K of 1 and 4, with and without
// its occupancy map (the fill gather, the count pass, the insert gather),
// the CPU's counters and lists in every runnable mode; lossless mode grows
// K as the CPU does.
TEST(Vulkan, TheKBufferGivesTheCpuListsAndCountersWithAndWithoutItsOccupancyMap) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());  // each mode run, not the chosen one
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const Extent screen{23 + 5 * static_cast<std::uint32_t>(seed), 15};
      const std::vector<Fragment> f =
          test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 2500 + 500 * seed, seed);
      for (std::uint32_t k : {1u, 4u})
        for (bool occupancy : {false, true}) {
          SCOPED_TRACE(to_string(mode) + " seed " + std::to_string(seed) + " k " + std::to_string(k) + " occupancy " +
                       std::to_string(occupancy));
          TechniqueConfig c = test::technique_config(Technique::KBuffer, screen, layout);
          c.layers = k;
          c.occupancy = occupancy;
          c.occupancy_words = 2;
          const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 1);
          const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, f);
          EXPECT_GT(cpu.counters.dropped_layers + cpu.counters.occupancy_rejected, 0u);
          EXPECT_EQ(gpu.counters, cpu.counters);
          EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
          if (k != 1 || occupancy) continue;
          const TechniqueBuild grown_cpu = build_technique(c, {}, f, {}, {}, 8);
          const TechniqueBuild grown_gpu = vk::build_technique_on_vulkan(context(), c, {}, f, {}, 8);
          ASSERT_EQ(grown_gpu.attempts.size(), grown_cpu.attempts.size());
          EXPECT_EQ(grown_gpu.lossless(), grown_cpu.lossless());
          EXPECT_EQ(grown_gpu.counters, grown_cpu.counters);
          EXPECT_EQ(grown_gpu.attempts.back().capacity, grown_cpu.attempts.back().capacity);
          EXPECT_EQ(test::traversed_lists(*grown_gpu.buffer), test::traversed_lists(*grown_cpu.buffer));
        }
    }
  }
}

// Fixed arrays and paged lists as the GL tests check them (test_gl_peers,
// test_gl_paged_lists): the CPU's counters and lists in every runnable
// mode, K too small and a pool too small included; lossless mode grows K
// and the pool as the CPU does.
TEST(Vulkan, FixedArraysAndPagedListsGiveTheCpuListsAndCountersInEveryRunnableMode) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());
    const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const Extent screen{21 + 6 * static_cast<std::uint32_t>(seed), 13 + static_cast<std::uint32_t>(seed)};
      const std::vector<Fragment> f =
          test::stream(screen, seed == 2 ? StreamKind::Hot : StreamKind::Coherent, 2000 + 800 * seed, seed);
      for (std::uint32_t k : {2u, 16u}) {
        SCOPED_TRACE(to_string(mode) + " arrays seed " + std::to_string(seed) + " k " + std::to_string(k));
        TechniqueConfig c = test::technique_config(Technique::Arrays, screen, layout);
        c.layers = k;
        const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 1);
        const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, f);
        EXPECT_EQ(gpu.counters, cpu.counters);
        // A full pixel keeps its first K arrivals, and the device's arrival
        // order is not the stream's: the lists are the CPU's where no pixel overflowed.
        if (cpu.counters.failures() == 0) {
          EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
        }
        if (k != 2) continue;
        EXPECT_GT(cpu.counters.failures(), 0u);  // K of 2 drops fragments: lossless mode grows K
        const TechniqueBuild grown_cpu = build_technique(c, {}, f, {}, {}, 4);
        const TechniqueBuild grown_gpu = vk::build_technique_on_vulkan(context(), c, {}, f, {}, 4);
        ASSERT_EQ(grown_gpu.attempts.size(), grown_cpu.attempts.size());
        EXPECT_TRUE(grown_gpu.lossless());
        EXPECT_EQ(grown_gpu.attempts.back().capacity, grown_cpu.attempts.back().capacity);
        EXPECT_EQ(test::traversed_lists(*grown_gpu.buffer), test::traversed_lists(*grown_cpu.buffer));
      }
      for (std::uint64_t pool : {std::uint64_t{0}, std::uint64_t{f.size() / 3}, std::uint64_t{4 * f.size()}}) {
        SCOPED_TRACE(to_string(mode) + " paged-lists seed " + std::to_string(seed) + " pool " + std::to_string(pool));
        TechniqueConfig c = test::technique_config(Technique::PagedLists, screen, layout);
        c.pool_capacity = pool;
        const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 4);
        const TechniqueBuild gpu = vk::build_technique_on_vulkan(context(), c, {}, f, {}, 4);
        // Racing calls of one pixel can each take a page when its page is
        // full, one of them linked (the device's wasted pages, counted in
        // the nodes asked for): the device's pool may take another attempt
        // and grow further than the CPU's, by how the calls raced. The
        // lossless result is the CPU's.
        EXPECT_TRUE(gpu.lossless());
        EXPECT_TRUE(cpu.lossless());
        EXPECT_EQ(gpu.counters, cpu.counters);
        EXPECT_GE(gpu.attempts.back().capacity, cpu.attempts.back().capacity);
        EXPECT_EQ(test::traversed_lists(*gpu.buffer), test::traversed_lists(*cpu.buffer));
      }
    }
  }
}

// SPEC 7 on Vulkan: the resolve pass composites each technique's lists over
// per-pixel backgrounds into the CPU's composite_image, float for float,
// on a multisampled screen too; backgrounds of the wrong count are refused
// naming both sizes.
TEST(Vulkan, TheResolvePassGivesTheCpuImageBitForBitForEveryTechniqueItRuns) {
  REQUIRE_VULKAN();
  for (AtomicMode mode : vk::runnable_atomic_modes(context().info())) {
  const ScopedEnv forced("HABUFFER_ATOMIC_MODE", std::string(to_string(mode)).c_str());
  const Layout layout = mode == AtomicMode::Native32 ? Layout::L32 : Layout::L64;
  for (std::uint32_t samples : {1u, 4u})
    for (Technique t : {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::Arrays, Technique::KBuffer,
                        Technique::PagedLists}) {
      if (samples > 1 && (t == Technique::KBuffer || t == Technique::Arrays))
        continue;  // multisampled screens are the lists' and the HA-buffer's (refuse_samples)
      SCOPED_TRACE(to_string(mode) + " " + to_string(t) + " samples " + std::to_string(samples));
      const Extent screen{37, 21};
      TechniqueConfig c = test::technique_config(t, screen, layout);
      c.buffer.samples = samples;
      if (t == Technique::KBuffer) c.layers = 4;
      std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 3000, 9);
      if (samples > 1)
        for (std::size_t i = 0; i < f.size(); ++i) f[i].coverage = 1u + static_cast<std::uint32_t>(i % 15);
      std::vector<glm::vec3> backgrounds(screen.area());
      for (std::size_t i = 0; i < backgrounds.size(); ++i)
        backgrounds[i] = glm::vec3(static_cast<float>(i % 7) / 7.0f, 0.25f, static_cast<float>(i % 3) / 3.0f);
      const TechniqueBuild cpu = build_technique(c, {}, f, {}, {}, 4);
      vk::VulkanResolve resolve;
      resolve.backgrounds = backgrounds;
      const TechniqueBuild gpu = vk::build_and_resolve_on_vulkan(context(), c, {}, f, resolve, {}, 4);
      EXPECT_EQ(gpu.counters, cpu.counters);
      const std::vector<glm::vec4> want = cpu.buffer->composite_image(backgrounds, 1);
      ASSERT_EQ(resolve.image.size(), want.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < want.size(); ++i) differ += resolve.image[i] != want[i];
      EXPECT_EQ(differ, 0u) << "of " << want.size() << " pixels";
      EXPECT_GT(resolve.resolve_ms, 0.0);
    }
  }
  TechniqueConfig c = test::technique_config(Technique::Ha, Extent{8, 8}, Layout::L64);
  const std::vector<glm::vec3> few(10);
  vk::VulkanResolve bad;
  bad.backgrounds = few;
  try {
    (void)vk::build_and_resolve_on_vulkan(context(), c, {}, {}, bad);
    ADD_FAILURE() << "backgrounds of the wrong count were taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("screen 8x8 (64), given 10"), std::string::npos) << e.what();
  }
}

TEST(Vulkan, MisuseThroughTheApiIsRefusedInOneLine) {
  REQUIRE_VULKAN();
  TechniqueConfig c;
  c.technique = Technique::Ha;
  c.buffer = test::config({16, 16}, {16, 16});
  const auto f = test::stream(c.buffer.screen, StreamKind::Random, 100, 1);
  // A technique without a Vulkan part yet, named with those that have one.
  TechniqueConfig wboit = c;
  wboit.technique = Technique::Wboit;
  const std::string e1 = error_of([&] { vk::build_technique_on_vulkan(context(), wboit, {}, f); });
  EXPECT_NE(e1.find("does not run wboit yet (it runs ha, lists, sorted-lists, arrays, kbuffer, paged-lists)"),
            std::string::npos)
      << e1;
  // A fragment off the screen, named.
  auto off = f;
  off[7].x = 16;
  const std::string e2 = error_of([&] { vk::build_technique_on_vulkan(context(), c, {}, off); });
  EXPECT_NE(e2.find("fragment 7"), std::string::npos) << e2;
  // A mode that is no mode, named.
  {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", "native128");
    const std::string e3 = error_of([&] { vk::build_technique_on_vulkan(context(), c, {}, f); });
    EXPECT_NE(e3.find("HABUFFER_ATOMIC_MODE='native128' is not native32, native64 or emulated64"), std::string::npos)
        << e3;
  }
  {
    const ScopedEnv forced("HABUFFER_ATOMIC_MODE", "native32");
    const std::string e4 = error_of([&] { vk::build_technique_on_vulkan(context(), c, {}, f); });
    EXPECT_NE(e4.find("does not fit layout L64"), std::string::npos) << e4;
  }
  // No attempts, a pipeline with a binding left unbound.
  EXPECT_NE(error_of([&] { vk::build_technique_on_vulkan(context(), c, {}, f, {}, 0); }).find("at least one"),
            std::string::npos);
  const auto spirv = vk::compile_to_spirv(vk::vulkan_insert_stream_compute(Technique::Ha, AtomicMode::Native32),
                                          vk::SpirvStage::Compute, "insert");
  vk::ComputePipeline pipeline(context(), spirv, "insert");
  const vk::VulkanBuffer one(context(), 64);
  const std::vector<vk::BoundBuffer> some{{0, &one}, {1, &one}};
  const std::string e5 = error_of([&] {
    context().submit_and_wait([&](VkCommandBuffer cmd) { pipeline.record(cmd, some, 1, 1); }, "unbound");
  });
  EXPECT_NE(e5.find("insert: binding 2 left unbound"), std::string::npos) << e5;
}

}  // namespace
}  // namespace habuffer
