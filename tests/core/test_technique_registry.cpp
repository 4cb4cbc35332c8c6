// The technique registry (issue 24): every enumerator has one descriptor at
// its place; the README's property table is the one the descriptors write;
// and what each descriptor claims holds on a stream: exact techniques give
// the exact lists, lists come out nearest first, the memory model is what
// the container allocates, the options it takes are the ones its
// configuration accepts, and lossless growth reaches a build that drops
// nothing.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"
#include "habuffer/technique_descriptor.h"
#include "test_support.h"

namespace habuffer {
namespace {

// A configuration of `d` that holds all of `frags` (the HA-buffer's table
// grows by lossless attempts).
TechniqueConfig roomy_config(const TechniqueDescriptor& d, Extent screen, std::span<const Fragment> frags) {
  TechniqueConfig c = test::technique_config(d.technique, screen);
  c.pool_capacity = frags.size();
  c.layers = test::depth_complexity(frags, screen);
  return c;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(TechniqueRegistry, ListsEveryEnumeratorOnceAtItsPlaceAndNamesParseBack) {
  const auto registry = technique_registry();
  ASSERT_EQ(registry.size(), all_techniques().size());
  for (std::size_t i = 0; i < registry.size(); ++i) {
    const TechniqueDescriptor& d = *registry[i];
    EXPECT_EQ(static_cast<std::size_t>(d.technique), i) << d.name;
    EXPECT_EQ(&descriptor(d.technique), &d);
    EXPECT_EQ(parse_technique(d.name), d.technique);
    EXPECT_EQ(find_technique(d.name), &d);
    EXPECT_FALSE(d.summary.empty()) << d.name;
    EXPECT_TRUE(d.validate && d.memory_bytes && d.paper_memory_bytes && d.make && d.grown) << d.name;
    EXPECT_EQ(d.stores_lists, !d.lossless_hint.empty()) << d.name << ": a technique that drops says how to keep it";
  }
  EXPECT_EQ(find_technique("paged"), nullptr);
  EXPECT_EQ(parse_technique("HA"), std::nullopt);
}

TEST(TechniqueRegistry, TheReadmePropertyTableIsTheOneTheDescriptorsWrite) {
  const std::string readme = file_text(HABUFFER_SOURCE_DIR "/README.md");
  const std::string begin = "<!-- technique properties: habuffer techniques --markdown -->\n";
  const std::string end = "<!-- end of technique properties -->";
  const std::size_t b = readme.find(begin), e = readme.find(end);
  ASSERT_NE(b, std::string::npos) << "README.md lacks the marker " << begin;
  ASSERT_NE(e, std::string::npos) << "README.md lacks the marker " << end;
  EXPECT_EQ(readme.substr(b + begin.size(), e - b - begin.size()), property_table_markdown())
      << "README.md's property table is stale: replace it by `build/bin/habuffer techniques --markdown`";
}

TEST(TechniqueRegistry, ExactTechniquesGiveTheExactListsNearestFirstOverSeeds) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Extent screen{13 + static_cast<std::uint32_t>(seed) * 5, 9 + static_cast<std::uint32_t>(seed)};
    const std::vector<Fragment> frags = test::stream(screen, StreamKind::Hot, 300 + seed * 200, seed);
    const test::ExactLists exact = test::exact_lists(frags, RecordLayout(Layout::L64, 8));
    for (const TechniqueDescriptor* d : technique_registry()) {
      if (!d->stores_lists) continue;
      const TechniqueBuild b =
          build_technique(roomy_config(*d, screen, frags), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 16);
      ASSERT_EQ(b.counters.failures(), 0u) << d->name << ", seed " << seed;
      const test::ExactLists lists = test::traversed_lists(*b.buffer);
      for (const auto& [pixel, entries] : lists)
        for (std::size_t i = 1; i < entries.size(); ++i)
          ASSERT_GT(entries[i - 1].code, entries[i].code) << d->name << ": not nearest first at pixel " << pixel.first
                                                          << "," << pixel.second;
      if (d->exact) {
        EXPECT_EQ(lists, exact) << d->name << ", seed " << seed;
      }
    }
  }
}

TEST(TechniqueRegistry, TheMemoryModelIsWhatEveryContainerAllocatesToTheByte) {
  for (const Extent screen : {Extent{40, 30}, Extent{7, 19}})
    for (const TechniqueDescriptor* d : technique_registry())
      for (bool extras : {false, true}) {
        TechniqueConfig c = test::technique_config(d->technique, screen);
        c.buffer.table = {screen.x + 5, screen.y + 2};
        c.pool_capacity = 333;
        c.layers = 3;
        if (extras && d->early_cull) c.buffer.early_cull_tau = 0.9f, c.buffer.saturation = true;
        if (extras && d->takes("occupancy")) c.occupancy = true, c.occupancy_words = 2;
        const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(c, OffsetSource{});
        EXPECT_EQ(memory_model_bytes(c, b->capacity()), b->memory_bytes()) << d->name << " " << screen.str();
        EXPECT_EQ(memory_model_bytes(*b), b->memory_bytes()) << d->name;
        EXPECT_EQ(c.configured_capacity(), b->capacity()) << d->name;
        EXPECT_GT(d->paper_memory_bytes(screen.area(), 1000, 0.5, 3), 0.0) << d->name;
      }
}

TEST(TechniqueRegistry, TheOptionsADescriptorTakesAreTheOnesItsConfigurationAccepts) {
  const Extent screen{16, 16};
  for (const TechniqueDescriptor* d : technique_registry()) {
    TechniqueConfig c = test::technique_config(d->technique, screen);
    c.pool_capacity = 100;
    TechniqueConfig culled = c;
    culled.buffer.early_cull_tau = 0.9f;
    EXPECT_EQ(culled.limit().empty(), d->takes("early-cull")) << d->name << ": " << culled.limit();
    EXPECT_EQ(d->early_cull, d->takes("early-cull")) << d->name;
    TechniqueConfig occupied = c;
    occupied.occupancy = true;
    EXPECT_EQ(occupied.limit().empty(), d->takes("occupancy")) << d->name << ": " << occupied.limit();
    EXPECT_EQ(d->takes("pool"), d->capacity == CapacityKind::PoolNodes) << d->name;
    EXPECT_EQ(d->takes("layers"), d->capacity == CapacityKind::PixelLayers) << d->name;
    EXPECT_EQ(d->takes("table"), d->capacity == CapacityKind::TableSlots) << d->name;
    EXPECT_EQ(d->takes("lossless"), d->stores_lists) << d->name;
    EXPECT_EQ(d->takes("depth-range"), d->reads_depth_range) << d->name;
  }
  EXPECT_EQ(techniques_taking("early-cull"), "ha, sorted-lists");
  EXPECT_EQ(techniques_taking("no-such-option"), "");
}

TEST(TechniqueRegistry, LosslessGrowthReachesABuildThatDropsNothing) {
  const Extent screen{24, 16};
  const std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 1500, 5);
  for (const TechniqueDescriptor* d : technique_registry()) {
    if (!d->stores_lists) continue;
    TechniqueConfig c = test::technique_config(d->technique, screen);
    c.pool_capacity = 10;
    c.layers = 1;
    const TechniqueBuild b = build_technique(c, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
    EXPECT_TRUE(b.lossless()) << d->name << " after " << b.attempts.size() << " attempts";
    EXPECT_EQ(b.counters.stored(), b.buffer->count_stored()) << d->name;
    if (d->capacity != CapacityKind::None) {
      EXPECT_GT(b.attempts.size(), 1u) << d->name << " grew nothing";
    }
  }
}

TEST(TechniqueRegistry, ConfigurationsDifferingOnlyInFieldsTheTechniqueIgnoresAreTheSameContainer) {
  for (const TechniqueDescriptor* d : technique_registry()) {
    TechniqueConfig a = test::technique_config(d->technique, {8, 8});
    a.pool_capacity = 50;
    TechniqueConfig b = a;
    if (d->capacity != CapacityKind::PoolNodes) b.pool_capacity = 77;
    if (d->capacity != CapacityKind::PixelLayers) b.layers = 9;
    if (!d->reads_depth_range) b.depth_range = {0.25f, 0.5f};
    EXPECT_EQ(a.relevant(), b.relevant()) << d->name;
    TechniqueConfig other = a;
    other.buffer.screen = {9, 8};
    other.buffer.table = {9, 8};
    EXPECT_NE(a.relevant(), other.relevant()) << d->name;
  }
}

}  // namespace
}  // namespace habuffer
