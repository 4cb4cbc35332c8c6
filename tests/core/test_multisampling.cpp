// Multisampled records (issue 37; docs/spec-notes.md, "Multisampled
// records"): every technique that stores lists keeps each fragment's S-bit
// coverage mask in the low bits of its code field, records of one depth and
// colour merge only when their masks are equal, and the per-pixel resolve
// composites each sample's own records and averages them. The expected
// codes below are SPEC 2's formula written out here, not the layout's code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "habuffer/interchange.h"
#include "habuffer/lossless_build.h"
#include "habuffer/reference_compositor.h"
#include "test_support.h"

namespace habuffer {
namespace {

constexpr std::uint32_t kAgeBits = 8;

// SPEC 2's depth code with D = 32 - A - S bits, shifted over the S mask bits.
std::uint32_t expected_code(float t, std::uint32_t samples) {
  const std::uint32_t c = samples > 1 ? samples : 0;
  const std::uint32_t d = 32 - kAgeBits - c;
  const std::uint64_t top = (std::uint64_t{1} << d) - 1;
  const auto q = static_cast<std::uint64_t>(std::floor(static_cast<double>(t) * std::ldexp(1.0, static_cast<int>(d))));
  return static_cast<std::uint32_t>((top - std::min(top, q)) << c);
}

// The mask a coverage word gives at S samples: 0 is every sample.
std::uint32_t expected_mask(std::uint32_t coverage, std::uint32_t samples) {
  const std::uint32_t all = (1u << samples) - 1u;
  return coverage == 0 ? all : coverage & all;
}

// Each pixel's distinct (code | mask, data) records, nearest first, larger
// mask then larger data first on a tie: what every exact technique stores.
test::ExactLists expected_lists(const std::vector<Fragment>& frags, std::uint32_t samples) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::set<std::pair<std::uint32_t, std::uint32_t>>> sets;
  for (const Fragment& f : frags) {
    const std::uint32_t mask = expected_mask(f.coverage, samples);
    if (!RecordLayout::depth_valid(f.depth) || mask == 0) continue;
    sets[{f.x, f.y}].insert({expected_code(f.depth, samples) | mask, f.rgba});
  }
  test::ExactLists out;
  for (const auto& [p, s] : sets)
    for (auto it = s.rbegin(); it != s.rend(); ++it) out[p].push_back({0, it->first, it->second});
  return out;
}

TechniqueConfig config_of(Technique t, Extent screen, std::uint32_t samples, std::size_t fragments) {
  TechniqueConfig c = test::technique_config(t, screen);
  c.buffer.samples = samples;
  if (uses_pool(t)) c.pool_capacity = fragments + 1;
  if (uses_layers(t)) c.layers = 64;
  if (t == Technique::Ha) c.buffer.table = Extent{screen.x * 2, screen.y * 2};
  return c;
}

const Technique kExact[] = {Technique::Ha, Technique::Lists, Technique::SortedLists, Technique::PagedLists,
                            Technique::Arrays, Technique::KBuffer};

std::vector<glm::vec3> striped_backgrounds(Extent screen) {
  std::vector<glm::vec3> b(screen.area());
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = glm::vec3(float(i % 5) / 5.0f, 0.5f, 1.0f - float(i % 3) / 3.0f);
  return b;
}

TEST(Multisampling, RecordsCarryTheMaskInTheLowBitsOfTheCodeFieldAndOneSampleKeepsSpec2sCode) {
  for (float t : {0.0f, 0.25f, 0.5f, 0.7312f, 1.0f}) {
    EXPECT_EQ(RecordLayout(Layout::L64, kAgeBits).depth_code(t), expected_code(t, 1)) << t;
    for (std::uint32_t s : {2u, 4u, 8u}) {
      const RecordLayout l(Layout::L64, kAgeBits, s);
      EXPECT_EQ(l.depth_bits(), 32 - kAgeBits - s);
      EXPECT_EQ(l.code_bits(), 32 - kAgeBits);
      EXPECT_EQ(l.depth_code(t), expected_code(t, s)) << t << " at " << s;
      EXPECT_EQ(l.fragment_code(t, 0b10u), expected_code(t, s) | 0b10u);
      EXPECT_EQ(l.fragment_code(t, 0), expected_code(t, s) | ((1u << s) - 1u)) << "no mask: every sample";
      const std::uint64_t r = l.pack(3, l.fragment_code(t, 0b01u), 0xAABBCCDDu);
      EXPECT_EQ(l.coverage(r), 0b01u);
      EXPECT_EQ(l.code(r) >> s, expected_code(t, s) >> s);
    }
  }
  const RecordLayout four(Layout::L64, kAgeBits, 4);
  EXPECT_FALSE(four.covers_sample(0x30u)) << "bits beyond the 4 samples cover none of them";
  EXPECT_TRUE(four.covers_sample(0x31u));
  EXPECT_TRUE(RecordLayout(Layout::L64, kAgeBits).covers_sample(0x30u)) << "one sample: the mask is not read";
}

TEST(Multisampling, EveryExactTechniqueStoresEachFragmentsMaskedRecordOverSeedsAndSampleCounts) {
  for (std::uint32_t samples : {2u, 4u, 8u})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Extent screen{23 + static_cast<std::uint32_t>(seed), 13};
      const std::vector<Fragment> frags = test::covered_stream(screen, 1500, seed, samples);
      const test::ExactLists expected = expected_lists(frags, samples);
      std::uint64_t invalid = 0;
      for (const Fragment& f : frags) invalid += expected_mask(f.coverage, samples) == 0 ? 1 : 0;
      ASSERT_GT(invalid, 0u) << "the stream has masks of no sample";
      for (Technique t : kExact) {
        const TechniqueBuild b =
            build_technique(config_of(t, screen, samples, frags.size()), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
        EXPECT_EQ(test::traversed_lists(*b.buffer), expected)
            << to_string(t) << ", " << samples << " samples, seed " << seed;
        EXPECT_EQ(b.counters.invalid, invalid) << to_string(t);
        EXPECT_EQ(b.counters.failures(), 0u) << to_string(t) << ": age " << b.counters.failed_age << ", iter "
                                             << b.counters.failed_iter << ", pool " << b.counters.dropped_pool
                                             << ", layers " << b.counters.dropped_layers;
      }
    }
}

TEST(Multisampling, RecordsOfOneDepthAndColourMergeOnlyWhenTheirMasksAreEqual) {
  const Extent screen{2, 1};
  const std::vector<Fragment> frags{{0, 0, 0.5f, 0xFF0000FFu, 0b0011u},
                                    {0, 0, 0.5f, 0xFF0000FFu, 0b1100u},
                                    {0, 0, 0.5f, 0xFF0000FFu, 0b0011u}};
  for (Technique t : kExact) {
    const TechniqueBuild b = build_technique(config_of(t, screen, 4, frags.size()), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
    EXPECT_EQ(b.counters.stored(), 2u) << to_string(t);
    EXPECT_EQ(b.counters.duplicates, 1u) << to_string(t);
    // The two halves of the pixel make a whole: every sample sees one opaque red record.
    const std::vector<glm::vec4> image = b.buffer->composite_image(std::vector<glm::vec3>(2, glm::vec3(1.0f)));
    EXPECT_EQ(image[0], glm::vec4(1.0f, 0.0f, 0.0f, 1.0f)) << to_string(t);
    EXPECT_EQ(image[1], glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)) << to_string(t);
  }
}

// Two fragments of one surface (one depth and colour) whose masks overlap
// stay two records, but a sample both cover blends the surface once: the
// per-sample form of SPEC 6's merge, so a doubled face does not darken the
// samples its two triangles share.
TEST(Multisampling, ASamplesDuplicateOfOneDepthAndColourBlendsOnce) {
  const Extent screen{1, 1};
  const std::vector<Fragment> doubled{{0, 0, 0.5f, 0x00FF0080u, 0b1111u}, {0, 0, 0.5f, 0x00FF0080u, 0b0011u},
                                      {0, 0, 0.25f, 0x0000FF40u, 0b0110u}};
  const std::vector<Fragment> single{{0, 0, 0.5f, 0x00FF0080u, 0b1111u}, {0, 0, 0.25f, 0x0000FF40u, 0b0110u}};
  for (Technique t : kExact) {
    const TechniqueBuild a = build_technique(config_of(t, screen, 4, 3), OffsetSource{}, doubled, InsertOptions{});
    const TechniqueBuild b = build_technique(config_of(t, screen, 4, 3), OffsetSource{}, single, InsertOptions{});
    EXPECT_EQ(a.counters.stored(), 3u) << to_string(t);
    const std::vector<glm::vec3> white(1, glm::vec3(1.0f));
    EXPECT_EQ(a.buffer->composite_image(white), b.buffer->composite_image(white)) << to_string(t);
  }
}

TEST(Multisampling, AHalfCoveredPixelBlendsItsColourIntoHalfItsSamples) {
  const Extent screen{1, 1};
  const std::vector<Fragment> frags{{0, 0, 0.25f, 0xFF0000FFu, 0b0101u}};
  for (Technique t : kExact) {
    const TechniqueBuild b = build_technique(config_of(t, screen, 4, 1), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
    const std::vector<glm::vec4> image = b.buffer->composite_image(std::vector<glm::vec3>(1, glm::vec3(1.0f)));
    EXPECT_EQ(image[0], glm::vec4(1.0f, 0.5f, 0.5f, 0.5f)) << to_string(t);
  }
}

TEST(Multisampling, ThePerPixelResolveMatchesThePerSampleReferenceAndEveryExactTechniqueAgreesBitForBit) {
  for (std::uint32_t samples : {2u, 4u, 8u}) {
    const Extent screen{31, 17};
    // Distinct depths within each pixel on a grid the codes resolve (D = 16
    // at 8 samples), so neither quantization nor a tie orders the lists
    // otherwise than the reference.
    std::vector<Fragment> frags = test::covered_stream(screen, 4000, samples, samples);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> seen;
    for (Fragment& f : frags) f.depth = static_cast<float>((seen[{f.x, f.y}]++ * 37u) % 4096u) / 4096.0f;
    const std::vector<glm::vec3> backgrounds = striped_backgrounds(screen);
    const std::vector<glm::dvec4> reference = reference_composite(frags, screen, backgrounds, samples);
    std::optional<std::vector<glm::vec4>> first;
    for (Technique t : kExact) {
      const TechniqueBuild b =
          build_technique(config_of(t, screen, samples, frags.size()), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
      const std::vector<glm::vec4> image = b.buffer->composite_image(backgrounds, 2);
      double worst = 0.0;
      for (std::size_t i = 0; i < image.size(); ++i)
        for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(image[i][c]) - reference[i][c]));
      EXPECT_LT(worst, 1e-5) << to_string(t) << " at " << samples << " samples";
      if (!first) first = image;
      else EXPECT_EQ(image, *first) << to_string(t) << " against ha at " << samples << " samples";
    }
  }
}

TEST(Multisampling, TheHaBuffersOnePixelCompositeIsThePerPixelResolveAndItRefusesToBeALightBuffer) {
  const Extent screen{9, 7};
  const std::vector<Fragment> frags = test::covered_stream(screen, 300, 4, 4);
  const TechniqueBuild b =
      build_technique(config_of(Technique::Ha, screen, 4, frags.size()), OffsetSource{}, frags, InsertOptions{},
                      ResizePolicy{}, 32);
  const HaBuffer& ha = *as_hash_table(*b.buffer);
  const glm::vec3 background(0.3f, 0.6f, 0.9f);
  const std::vector<glm::vec4> image = ha.composite_image(background, 1);
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) EXPECT_EQ(ha.composite(x, y, background), image[x + y * screen.x]);
  EXPECT_THROW((void)ha.transmittance(0, 0, 0, 0), std::invalid_argument);
}

TEST(Multisampling, ReversingTheDrawOrderGivesTheSameListsAndImage) {
  const Extent screen{19, 21};
  std::vector<Fragment> frags = test::covered_stream(screen, 3000, 7, 4);
  std::vector<Fragment> reversed(frags.rbegin(), frags.rend());
  const std::vector<glm::vec3> backgrounds = striped_backgrounds(screen);
  for (Technique t : kExact) {
    const TechniqueConfig c = config_of(t, screen, 4, frags.size());
    const TechniqueBuild a = build_technique(c, OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
    const TechniqueBuild b = build_technique(c, OffsetSource{}, reversed, InsertOptions{}, ResizePolicy{}, 32);
    EXPECT_EQ(test::traversed_lists(*a.buffer), test::traversed_lists(*b.buffer)) << to_string(t);
    EXPECT_EQ(a.buffer->composite_image(backgrounds), b.buffer->composite_image(backgrounds)) << to_string(t);
  }
}

TEST(Multisampling, OneSampleReadsNoMaskAndGivesTodaysListsAndImageByteForByte) {
  const Extent screen{27, 15};
  const std::vector<Fragment> masked = test::covered_stream(screen, 3000, 3, 4);
  std::vector<Fragment> plain = masked;
  for (Fragment& f : plain) f.coverage = 0;
  const std::vector<glm::vec3> backgrounds = striped_backgrounds(screen);
  for (Technique t : all_techniques()) {
    const TechniqueConfig c = config_of(t, screen, 1, masked.size());
    const TechniqueBuild a = build_technique(c, OffsetSource{}, masked, InsertOptions{}, ResizePolicy{}, 32);
    const TechniqueBuild b = build_technique(c, OffsetSource{}, plain, InsertOptions{}, ResizePolicy{}, 32);
    EXPECT_EQ(a.counters, b.counters) << to_string(t);
    EXPECT_EQ(a.buffer->composite_image(backgrounds), b.buffer->composite_image(backgrounds)) << to_string(t);
    if (stores_lists(t)) {
      EXPECT_EQ(test::traversed_lists(*a.buffer), test::traversed_lists(*b.buffer)) << to_string(t);
      EXPECT_EQ(test::traversed_lists(*a.buffer), test::exact_lists(plain, c.buffer.record_layout())) << to_string(t);
    }
  }
}

TEST(Multisampling, SampleCountsOutsideTheRulesAreRefusedInOneLineNamingTheValue) {
  const auto refused = [](const TechniqueConfig& c, const std::string& words) {
    try {
      c.validate();
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  TechniqueConfig c = config_of(Technique::Ha, Extent{4, 4}, 3, 1);
  refused(c, "samples 3 is not 1, 2, 4 or 8");
  c.buffer.samples = 16;
  refused(c, "samples 16 is not 1, 2, 4 or 8");
  c.buffer.samples = 4;
  c.buffer.early_cull_tau = 0.9f;
  refused(c, "early cull accumulates a whole pixel's opacity");
  refused(config_of(Technique::Wboit, Extent{4, 4}, 4, 1), "wboit stores none");
  EXPECT_THROW(reference_composite({}, Extent{1, 1}, glm::dvec3(1.0), 5), std::invalid_argument);
}

TEST(Multisampling, TheListsCsvGainsACoverageColumnAndStreamsKeepTheirMasks) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "habuffer_multisampling_test";
  std::filesystem::create_directories(dir);
  const Extent screen{3, 2};
  const std::vector<Fragment> frags{{1, 0, 0.5f, 0x10203040u, 0b0110u}, {1, 0, 0.25f, 0x50607080u, 0}};
  write_fragments((dir / "f.csv").string(), frags);
  EXPECT_EQ(read_fragments((dir / "f.csv").string(), screen), frags);
  std::vector<Fragment> whole = frags;
  for (Fragment& f : whole) f.coverage = 0;
  write_fragments((dir / "w.csv").string(), whole);
  std::ifstream w(dir / "w.csv");
  std::string header;
  std::getline(w, header);
  EXPECT_EQ(header, "x,y,depth,rgba") << "streams without masks keep SPEC 10's header";

  const TechniqueBuild b = build_technique(config_of(Technique::Lists, screen, 4, 2), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
  write_lists((dir / "l.csv").string(), *b.buffer);
  std::ifstream l(dir / "l.csv");
  std::stringstream text;
  text << l.rdbuf();
  EXPECT_EQ(text.str(), "x,y,rank,code,rgba,coverage\n1,0,0," + std::to_string(expected_code(0.25f, 4) >> 4) +
                            ",1348497536,15\n1,0,1," + std::to_string(expected_code(0.5f, 4) >> 4) + ",270544960,6\n");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace habuffer
