// The GPU traffic model (issue 36, part 7): its counts on hand-made streams
// whose sectors, lines, atomics, conflicts and chains are known.
#include <gtest/gtest.h>

#include <vector>

#include "habuffer/harness/gpu_model.h"
#include "habuffer/harness/warp_traffic.h"

namespace habuffer::harness {
namespace {

// One warp whose lane l records `accesses(l, recorder)`.
template <class F>
TrafficCounts one_warp(F accesses) {
  WarpRecorder r;
  for (std::uint32_t l = 0; l < WarpRecorder::kLanes; ++l) {
    r.begin_lane(l);
    accesses(l, r);
  }
  r.end_warp();
  return r.counts();
}

TEST(GpuTrafficModel, ThirtyTwoLanesLoadingConsecutiveWordsTouchFourSectorsOfOneLine) {
  const TrafficCounts c = one_warp([](std::uint32_t l, WarpRecorder& r) { r.record(1, 4096 + 4 * l, AccessKind::Load, true); });
  EXPECT_EQ(c.warps, 1u);
  EXPECT_EQ(c.lanes, 32u);
  EXPECT_EQ(c.instructions, 1u);
  EXPECT_EQ(c.sectors, 4u);
  EXPECT_EQ(c.lines, 1u);
  EXPECT_EQ(c.atomics, 0u);
  EXPECT_EQ(c.chain, 1u);
}

TEST(GpuTrafficModel, ScatteredLanesTouchASectorAndALineEach) {
  const TrafficCounts c = one_warp([](std::uint32_t l, WarpRecorder& r) { r.record(1, 128 * l, AccessKind::Store, false); });
  EXPECT_EQ(c.sectors, 32u);
  EXPECT_EQ(c.lines, 32u);
  EXPECT_EQ(c.chain, 0u);
}

TEST(GpuTrafficModel, AtomicsOnOneWordConflictThirtyOneTimesAndReductionsAreNoChainLink) {
  const TrafficCounts c = one_warp([](std::uint32_t, WarpRecorder& r) { r.record(1, 64, AccessKind::Reduction, false); });
  EXPECT_EQ(c.atomics, 32u);
  EXPECT_EQ(c.conflicts, 31u);
  EXPECT_EQ(c.sectors, 1u);
  EXPECT_EQ(c.chain, 0u);
}

TEST(GpuTrafficModel, TheWarpsChainIsItsLongestLaneAndSitesNeverShareAnInstruction) {
  // Lane 0 loads three times, the others once; lane 1's load is at another site.
  const TrafficCounts c = one_warp([](std::uint32_t l, WarpRecorder& r) {
    r.record(l == 1 ? 2 : 1, 4 * l, AccessKind::Load, true);
    if (l == 0) {
      r.record(1, 1024, AccessKind::Load, true);
      r.record(1, 2048, AccessKind::Load, true);
    }
  });
  EXPECT_EQ(c.instructions, 4u);  // step 0 at two sites, steps 1 and 2
  EXPECT_EQ(c.chain, 3u);
  EXPECT_EQ(c.chain_max, 3u);
  EXPECT_EQ(c.accesses, 34u);
}

// 32 fragments of pixels (x0 + i * dx, 0), depths growing (each behind the one before).
std::vector<Fragment> row_stream(std::uint32_t dx) {
  std::vector<Fragment> s;
  for (std::uint32_t i = 0; i < 32; ++i) s.push_back({i * dx, 0, 0.01f * static_cast<float>(i + 1), 0x80808080u});
  return s;
}

TechniqueConfig config(Technique t, Extent screen) {
  TechniqueConfig c;
  c.technique = t;
  c.buffer.screen = screen;
  c.buffer.table = screen;
  c.buffer.age_bits = 6;
  c.layers = 4;
  return c;
}

// Offsets (a, 0) for age a + 1: pixel (0, 0)'s probes are slots 0, 1, 2, ...
OffsetSource line_offsets() {
  OffsetSource o;
  o.generator = OffsetGenerator::List;
  for (std::uint32_t a = 0; a < 63; ++a) o.list.emplace_back(a, 0);
  return o;
}

TEST(GpuTrafficModel, ListsOnThirtyTwoNeighbouringPixelsCoalesceButAllocateFromOneCounter) {
  const GpuTraffic t = model_gpu_frame(config(Technique::Lists, {32, 1}), {}, row_stream(1));
  // node counter (1 sector, 31 conflicts), entries (8 sectors, 2 lines), heads (4, 1), links (4, 1),
  // tallies (a 64-byte stripe each: 32 sectors, 16 lines).
  EXPECT_EQ(t.gather.instructions, 5u);
  EXPECT_EQ(t.gather.sectors, 49u);
  EXPECT_EQ(t.gather.lines, 21u);
  EXPECT_EQ(t.gather.atomics, 96u);
  EXPECT_EQ(t.gather.conflicts, 31u);
  EXPECT_EQ(t.gather.chain, 2u);  // the node counter, then the head exchange
  // Sort of one-node lists: head, length walk, entry and link into the private array, the entry and link back.
  EXPECT_EQ(t.sort.instructions, 7u);
  EXPECT_EQ(t.sort.sectors, 36u);
  EXPECT_EQ(t.sort.chain, 5u);
  // Composite: head, entry, link.
  EXPECT_EQ(t.resolve.instructions, 3u);
  EXPECT_EQ(t.resolve.sectors, 16u);
  EXPECT_EQ(t.resolve.lines, 4u);
  EXPECT_EQ(t.resolve.chain, 3u);
}

TEST(GpuTrafficModel, ListsOnOnePixelSerializeTheHeadAndTheTallyToo) {
  const GpuTraffic t = model_gpu_frame(config(Technique::Lists, {32, 1}), {}, row_stream(0));
  EXPECT_EQ(t.gather.sectors, 1u + 8u + 1u + 4u + 1u);
  EXPECT_EQ(t.gather.atomics, 96u);
  EXPECT_EQ(t.gather.conflicts, 93u);
}

TEST(GpuTrafficModel, ArraysOnThirtyTwoNeighbouringPixelsCountAndStoreCoalesced) {
  const GpuTraffic t = model_gpu_frame(config(Technique::Arrays, {32, 1}), {}, row_stream(1));
  // count add (4 sectors, 1 line), layer 0 store (8, 2), tallies (32, 16)
  EXPECT_EQ(t.gather.sectors, 44u);
  EXPECT_EQ(t.gather.lines, 19u);
  EXPECT_EQ(t.gather.atomics, 64u);
  EXPECT_EQ(t.gather.conflicts, 0u);
  EXPECT_EQ(t.gather.chain, 1u);
}

TEST(GpuTrafficModel, TheKBufferOnThirtyTwoNeighbouringPixelsReadsThenRaisesItsFirstLayer) {
  const GpuTraffic t = model_gpu_frame(config(Technique::KBuffer, {32, 1}), {}, row_stream(1));
  // slot read (8 sectors, 2 lines), its atomicMax (8, 2), tallies (32, 16)
  EXPECT_EQ(t.gather.sectors, 48u);
  EXPECT_EQ(t.gather.lines, 20u);
  EXPECT_EQ(t.gather.atomics, 64u);
  EXPECT_EQ(t.gather.chain, 2u);
  // Composite: layer 0 holds the record, layer 1 is empty and ends the walk.
  EXPECT_EQ(t.resolve.instructions, 2u);
  EXPECT_EQ(t.resolve.chain, 2u);
}

TEST(GpuTrafficModel, TheHaBufferOnThirtyTwoNeighbouringPixelsProbesOneCoalescedRow) {
  const GpuTraffic t = model_gpu_frame(config(Technique::Ha, {64, 64}), line_offsets(), row_stream(1));
  // offset O[0] (one sector for all), slot atomics on slots 0..31 (8 sectors, 2 lines),
  // max-age cells 0..3 (1 sector, 28 conflicts), tallies (32, 16)
  EXPECT_EQ(t.gather.instructions, 4u);
  EXPECT_EQ(t.gather.sectors, 42u);
  EXPECT_EQ(t.gather.lines, 20u);
  EXPECT_EQ(t.gather.atomics, 96u);
  EXPECT_EQ(t.gather.conflicts, 28u);
  EXPECT_EQ(t.gather.chain, 1u);
  EXPECT_EQ(t.sort.instructions, 0u);
}

TEST(GpuTrafficModel, TheHaBufferOnOnePixelProbesOneAgeMorePerFragmentOnOneSlotEach) {
  const GpuTraffic t = model_gpu_frame(config(Technique::Ha, {64, 64}), line_offsets(), row_stream(0));
  // Fragment k (each behind the last) loses ages 1..k and lands at age k + 1: 1 + 2 + ... + 32 slot
  // atomics, the lanes still probing age a all on one slot, then a max-age raise and a tally each.
  EXPECT_EQ(t.gather.atomics, 528u + 32u + 32u);
  EXPECT_EQ(t.gather.conflicts, 496u);
  EXPECT_EQ(t.gather.chain, 32u);
  EXPECT_EQ(t.gather.chain_max, 32u);
}

TEST(GpuTrafficModel, TheCostModelPricesEachPassAndRefusesTechniquesWithoutATracedKernel) {
  GpuCostModel m;
  m.gather_frame_ms = 1;
  m.gather_instruction_ns = 2;
  m.resolve_frame_ms = 3;
  m.resolve_instruction_ns = 4;
  m.sector_ns = 5;
  GpuTraffic t;
  t.gather.instructions = 1000;
  t.gather.sectors = 10000;
  t.gather.atomics = 7;  // counted, not priced
  t.sort.instructions = 100;
  t.sort.sectors = 200;
  t.resolve.instructions = 300;
  t.resolve.sectors = 400;
  EXPECT_DOUBLE_EQ(m.gather_ms(t), 1 + (2000 + 50000) * 1e-6);
  EXPECT_DOUBLE_EQ(m.resolve_ms(t), 3 + (4 * 400 + 5 * 600) * 1e-6);
  EXPECT_FALSE(gpu_model_covers(Technique::Wboit));
  EXPECT_THROW((void)model_gpu_frame(config(Technique::Wboit, {32, 1}), {}, row_stream(1)), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer::harness
