// The remaining peers behind the same interface: lists kept sorted while
// inserting (with early termination and saturation depth), the k-buffer
// (with its occupancy map), and the two baselines that store no lists
// (weighted blended OIT, plain blending). CPU path; test_gl_peers.cpp
// checks the GL path against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "habuffer/techniques/blended/blended_image.h"
#include "habuffer/techniques/blended/detail/blended_kernel.h"
#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"
#include "habuffer/reference_compositor.h"
#include "test_support.h"

namespace habuffer {
namespace {

using test::ExactLists;

ExactLists first_k(ExactLists lists, std::size_t k) {
  for (auto& [p, list] : lists)
    if (list.size() > k) list.resize(k);
  return lists;
}

InsertOptions threads(std::uint32_t n) {
  InsertOptions o;
  o.threads = n;
  o.mode = n == 1 ? InsertMode::Serial : InsertMode::Atomic;
  return o;
}

// Full-screen planes of one opacity at distinct depths, front to back or back to front.
std::vector<Fragment> planes(Extent screen, std::uint32_t count, bool front_first, std::uint32_t alpha) {
  std::vector<Fragment> f;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t layer = front_first ? k : count - 1 - k;
    const float t = 0.1f + 0.8f * static_cast<float>(layer) / static_cast<float>(count);
    const std::uint32_t rgba = ((40u + 7u * layer) << 24) | ((200u - 5u * layer) << 16) | (90u << 8) | alpha;
    for (std::uint32_t y = 0; y < screen.y; ++y)
      for (std::uint32_t x = 0; x < screen.x; ++x) f.push_back({x, y, t, rgba});
  }
  return f;
}

double worst_error(const std::vector<glm::vec4>& image, const std::vector<glm::dvec4>& reference) {
  double worst = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i)
    for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(double(image[i][ch]) - reference[i][ch]));
  return worst;
}

TEST(SortedLists, GiveTheHaBuffersListsByteForByteOverSeedsStreamsAndThreads) {
  for (const auto& [kind, layout] : {std::pair{StreamKind::Coherent, Layout::L64}, std::pair{StreamKind::Random, Layout::L64},
                                     std::pair{StreamKind::Hot, Layout::L64}, std::pair{StreamKind::Hot, Layout::L32}})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const Extent screen{19 + static_cast<std::uint32_t>(seed) * 2, 13};
      const std::vector<Fragment> frags = test::stream(screen, kind, 500 + seed * 200, seed);
      BuildResult ha = build(test::config(screen, screen, layout), OffsetSource{}, frags, InsertOptions{}, ResizePolicy{}, 32);
      ASSERT_TRUE(ha.lossless());
      const ExactLists expected = test::traversed_lists(ha.buffer);
      for (std::uint32_t n : {1u, 4u}) {
        TechniqueConfig c = test::technique_config(Technique::SortedLists, screen, layout);
        c.pool_capacity = frags.size();
        LinkedLists sorted(c);
        const Counters counters = sorted.insert(test::shuffled(frags, seed + n), threads(n));
        EXPECT_EQ(test::traversed_lists(sorted), expected) << "seed " << seed << " threads " << n;
        EXPECT_EQ(counters, ha.counters) << "seed " << seed << " threads " << n;
        EXPECT_EQ(sorted.count_stored(), counters.stored());
      }
    }
}

TEST(SortedLists, AFullPoolDropsAndCountsAndDuplicatesTakeNoNode) {
  const Extent screen{8, 8};
  std::vector<Fragment> frags = test::stream(screen, StreamKind::Coherent, 300, 5);
  frags.insert(frags.end(), frags.begin(), frags.begin() + 50);  // 50 exact duplicates
  TechniqueConfig c = test::technique_config(Technique::SortedLists, screen);
  c.pool_capacity = 100;
  LinkedLists lists(c);
  const Counters n = lists.insert(frags);
  EXPECT_EQ(n.dropped_pool + n.stored() + n.duplicates + n.invalid, n.fragments);
  EXPECT_EQ(n.stored(), 100u);
  EXPECT_GT(n.dropped_pool, 0u);
  EXPECT_EQ(lists.count_stored(), 100u);
}

// Invariant 5 for early termination, with and without saturation depth, on
// both techniques with early cull: no fragment in front of opacity at most
// tau is lost, and the image is within (1 - tau) of the exact reference.
TEST(EarlyTermination, RespectsInvariant5WithAndWithoutSaturationOnBothTechniques) {
  const Extent screen{24, 24};
  const std::vector<Fragment> f = test::grid_stream(screen, 9000, 17, 40);
  const glm::dvec3 bg(0.2, 0.5, 0.9);
  const auto reference = reference_composite(f, screen, bg);
  for (Technique t : {Technique::Ha, Technique::SortedLists})
    for (float tau : {0.5f, 0.9f, 0.99f})
      for (bool saturation : {false, true})
        for (std::uint32_t n : {1u, 2u}) {
          SCOPED_TRACE(to_string(t) + " tau " + std::to_string(tau) + " saturation " + std::to_string(saturation) +
                       " threads " + std::to_string(n));
          TechniqueConfig c = test::technique_config(t, screen);
          c.buffer.table = {120, 120};
          c.buffer.early_cull_tau = tau;
          c.buffer.saturation = saturation;
          c.pool_capacity = f.size();
          const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(c, OffsetSource{});
          const Counters counts = b->insert(f, threads(n));
          ASSERT_EQ(counts.failures(), 0u);
          EXPECT_GT(counts.culled, 0u);
          EXPECT_EQ(counts.saturated_rejected > 0, saturation);
          EXPECT_EQ(b->count_stored(), counts.stored());
          std::vector<glm::vec3> backgrounds(screen.area(), glm::vec3(bg));
          EXPECT_LE(worst_error(b->composite_image(backgrounds, 1), reference), (1.0 - tau) + 1e-4);
          const auto kept = test::traversed_lists(*b);
          for (const auto& [p, list] : test::exact_lists(f, c.buffer.record_layout())) {
            double acc = 0.0;
            const auto it = kept.find(p);
            for (const ListEntry& e : list) {
              if (acc > tau - 1e-6) break;
              ASSERT_TRUE(it != kept.end() && std::find(it->second.begin(), it->second.end(), e) != it->second.end());
              acc += (1.0 - acc) * ((e.data & 255u) / 255.0);
            }
          }
        }
}

// Seed 001, Fig. 10: planes drawn front to back stop being stored once the
// pixel saturates; back to front, every plane lands in front of the last
// one, so early termination keeps them all (sorted lists), and only the
// HA-buffer's evicted records can still be culled.
TEST(EarlyTermination, FrontToBackPlanesStoreFarFewerThanBackToFrontAndSaturationRejectsTheRest) {
  const Extent screen{16, 8};
  const std::uint64_t pixels = screen.area();
  for (Technique t : {Technique::SortedLists, Technique::Ha}) {
    SCOPED_TRACE(to_string(t));
    const auto stored = [&](bool front_first, bool saturation) {
      TechniqueConfig c = test::technique_config(t, screen);
      c.buffer.table = {64, 64};
      c.buffer.early_cull_tau = 0.99f;
      c.buffer.saturation = saturation;
      c.pool_capacity = 32 * pixels;
      const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(c, OffsetSource{});
      return b->insert(planes(screen, 32, front_first, 128));
    };
    const Counters front = stored(true, false), back = stored(false, false);
    EXPECT_EQ(front.stored(), 7 * pixels);  // alpha 128/255: 1 - (127/255)^7 > 0.99 > 1 - (127/255)^6
    if (t == Technique::SortedLists) {
      EXPECT_EQ(back.stored(), 32 * pixels);
    } else {
      // The HA-buffer's evicted records accumulate the opacity of what evicted
      // them: it culls back to front as well, down to the same 7 per pixel.
      EXPECT_EQ(back.stored(), 7 * pixels);
    }
    const Counters front_saturated = stored(true, true), back_saturated = stored(false, true);
    // Front to back: the first culled plane saturates its pixel, every later one is rejected before insertion.
    EXPECT_EQ(front_saturated.stored(), front.stored());
    EXPECT_EQ(front_saturated.culled, pixels);
    EXPECT_EQ(front_saturated.saturated_rejected, front.culled - pixels);
    EXPECT_LE(back_saturated.stored(), back.stored());
  }
}

TEST(KBuffer, KeepsExactlyTheKNearestOfEachPixelWithAndWithoutOccupancy) {
  for (const auto& [kind, layout] : {std::pair{StreamKind::Coherent, Layout::L64}, std::pair{StreamKind::Hot, Layout::L64},
                                     std::pair{StreamKind::Random, Layout::L32}})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Extent screen{21, 9 + static_cast<std::uint32_t>(seed)};
      const std::vector<Fragment> frags = test::stream(screen, kind, 1500 + seed * 300, seed);
      const ExactLists exact = test::exact_lists(frags, RecordLayout(layout, 8));
      for (std::uint32_t k : {1u, 3u, 8u})
        for (bool occupancy : {false, true})
          for (std::uint32_t n : {1u, 3u}) {
            SCOPED_TRACE("k " + std::to_string(k) + " occupancy " + std::to_string(occupancy) + " seed " +
                         std::to_string(seed) + " threads " + std::to_string(n));
            TechniqueConfig c = test::technique_config(Technique::KBuffer, screen, layout);
            c.layers = k;
            c.occupancy = occupancy;
            c.occupancy_words = 1;
            KBuffer kb(c);
            const Counters counts = kb.insert(test::shuffled(frags, seed * k), threads(n));
            EXPECT_EQ(test::traversed_lists(kb), first_k(exact, k));
            EXPECT_EQ(counts.stored(), kb.count_stored());
            if (!occupancy) {
              EXPECT_EQ(counts.occupancy_rejected, 0u);
            } else if (k == 1) {
              EXPECT_GT(counts.occupancy_rejected, 0u);
            }
          }
    }
}

TEST(KBuffer, TheOccupancyLimitIsTheBucketOfTheKthOccupiedOne) {
  const Extent screen{2, 1};
  TechniqueConfig c = test::technique_config(Technique::KBuffer, screen);
  c.layers = 3;
  c.occupancy = true;
  c.occupancy_words = 1;  // 32 buckets over [0, 1]
  KBuffer kb(c);
  // Pixel 0: depths in buckets 2, 2, 5, 9, 30; the 3rd occupied bucket is 9.
  std::vector<Fragment> f;
  for (float t : {2.5f, 2.2f, 5.5f, 9.5f, 30.5f}) f.push_back({0, 0, t / 32.0f, 0x808080FFu});
  f.push_back({1, 0, 0.5f, 0x808080FFu});  // pixel 1: one bucket only
  const Counters n = kb.insert(f);
  EXPECT_EQ(kb.occupancy_limit(0, 0), 9u);
  EXPECT_EQ(kb.occupancy_limit(1, 0), 32u);
  EXPECT_EQ(n.occupancy_rejected, 1u);  // the fragment in bucket 30
  EXPECT_EQ(n.stored(), 4u);            // the 3 nearest of pixel 0, the one of pixel 1
  EXPECT_EQ(n.dropped_layers, 1u);      // bucket 9's fragment passed the map but is the 4th
}

// Wboit and blend against a CPU computation of their formulas in double
// precision: they depend on the order of the stream only through float
// rounding (wboit: sums and products; blend is order-dependent by
// definition, so the reference blends in the same stream order). The same
// stream inserted with several threads gives the serial image bit for bit
// (each pixel keeps its stream order).
TEST(Blended, WboitAndBlendMatchTheirFormulasComputedInDoubleWithinFloatTolerance) {
  const Extent screen{12, 10};
  const std::vector<Fragment> f = test::stream(screen, StreamKind::Coherent, 3000, 9);
  const glm::vec3 bg(0.3f, 0.6f, 0.1f);
  const std::vector<glm::vec3> backgrounds(screen.area(), bg);
  for (Technique t : {Technique::Wboit, Technique::Blend}) {
    SCOPED_TRACE(to_string(t));
    TechniqueConfig c = test::technique_config(t, screen);
    c.depth_range = {0.0f, 1.0f};
    BlendedImage image(c);
    const Counters n = image.insert(f);
    EXPECT_EQ(n.blended, f.size());
    EXPECT_EQ(n.stored(), 0u);
    EXPECT_EQ(image.count_stored(), 0u);
    const std::vector<glm::vec4> got = image.composite_image(backgrounds, 1);
    std::vector<glm::dvec4> accum(screen.area(), t == Technique::Blend ? glm::dvec4(0, 0, 0, 1) : glm::dvec4(0));
    std::vector<double> reveal(screen.area(), 1.0);
    for (const Fragment& x : f) {
      const std::size_t p = x.x + std::size_t{x.y} * screen.x;
      const glm::dvec4 col(double(x.rgba >> 24) / 255.0, double((x.rgba >> 16) & 255u) / 255.0,
                           double((x.rgba >> 8) & 255u) / 255.0, double(x.rgba & 255u) / 255.0);
      if (t == Technique::Blend) {
        accum[p] = glm::dvec4(col.a * glm::dvec3(col) + (1 - col.a) * glm::dvec3(accum[p]), (1 - col.a) * accum[p].a);
      } else {
        const double k = 1.0 - std::clamp(double(x.depth), 0.0, 1.0);
        const double w = col.a * std::max(1e-2, 3e3 * k * k * k);
        accum[p] += glm::dvec4(glm::dvec3(col) * col.a * w, col.a * w);
        reveal[p] *= 1.0 - col.a;
      }
    }
    double worst = 0.0;
    for (std::size_t p = 0; p < got.size(); ++p) {
      glm::dvec3 want;
      if (t == Technique::Blend) {
        want = glm::dvec3(accum[p]) + accum[p].a * glm::dvec3(bg);
      } else {
        const glm::dvec3 avg = glm::dvec3(accum[p]) / std::clamp(accum[p].a, 1e-4, 5e4);
        want = avg * (1 - reveal[p]) + glm::dvec3(bg) * reveal[p];
      }
      for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(double(got[p][ch]) - want[ch]));
    }
    EXPECT_LT(worst, 1e-5);
    BlendedImage parallel(c);
    EXPECT_EQ(parallel.insert(f, threads(3)), n);
    EXPECT_EQ(parallel.composite_image(backgrounds, 2), got);
  }
}

TEST(Peers, TheMemoryModelGivesWhatTheCpuContainersAllocateToTheByte) {
  for (const Extent screen : {Extent{64, 48}, Extent{17, 3}}) {
    TechniqueConfig c = test::technique_config(Technique::SortedLists, screen);
    c.pool_capacity = 333;
    c.buffer.early_cull_tau = 0.5f;
    for (bool saturation : {false, true}) {
      c.buffer.saturation = saturation;
      c.technique = Technique::SortedLists;
      EXPECT_EQ(memory_model_bytes(c, 333), LinkedLists(c).memory_bytes());
      c.technique = Technique::Ha;
      EXPECT_EQ(memory_model_bytes(c, screen.area()), make_fragment_buffer(c, OffsetSource{})->memory_bytes());
    }
    c.buffer.early_cull_tau = 0.0f;
    c.buffer.saturation = false;
    for (Layout layout : {Layout::L64, Layout::L32})
      for (bool occupancy : {false, true}) {
        c.technique = Technique::KBuffer;
        c.buffer.layout = layout;
        c.layers = 6;
        c.occupancy = occupancy;
        EXPECT_EQ(memory_model_bytes(c, 0), KBuffer(c).memory_bytes());
      }
    c.buffer.layout = Layout::L64;
    c.occupancy = false;
    for (Technique t : {Technique::Wboit, Technique::Blend}) {
      c.technique = t;
      EXPECT_EQ(memory_model_bytes(c, 0), BlendedImage(c).memory_bytes());
    }
  }
}

TEST(Peers, BadConfigurationsAreRefusedNamingTheField) {
  TechniqueConfig c = test::technique_config(Technique::Lists, {8, 8});
  c.pool_capacity = 10;
  c.buffer.early_cull_tau = 0.5f;
  EXPECT_THROW(c.validate(), std::invalid_argument);  // lists have no early cull
  c.technique = Technique::SortedLists;
  EXPECT_NO_THROW(c.validate());
  c.buffer.early_cull_tau = 0.0f;
  c.buffer.saturation = true;
  EXPECT_THROW(c.validate(), std::invalid_argument);  // saturation without cull
  c = test::technique_config(Technique::Arrays, {8, 8});
  c.occupancy = true;
  EXPECT_THROW(c.validate(), std::invalid_argument);  // occupancy is the k-buffer's
  c.technique = Technique::KBuffer;
  EXPECT_NO_THROW(c.validate());
  c.occupancy_words = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c.occupancy_words = 4;
  c.depth_range = {0.5f, 0.5f};
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = test::technique_config(Technique::Lists, {8, 8});
  c.pool_capacity = 10;
  EXPECT_THROW(BlendedImage{c}, std::invalid_argument);
}

}  // namespace
}  // namespace habuffer
