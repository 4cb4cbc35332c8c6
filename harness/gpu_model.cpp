#include "habuffer/harness/gpu_model.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/max_age_table.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_params.h"
#include "traced_kernels.h"

namespace habuffer::harness {
namespace {

// The gather: warps of 32 consecutive fragments, each lane one insert call
// (`call` returns its outcome) and its tally.
template <class Call>
TrafficCounts replay_gather(std::span<const Fragment> fragments, WarpRecorder& rec, const traced::Tracer& tracer,
                            Call call) {
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const Fragment& f = fragments[i];
    rec.begin_lane(static_cast<std::uint32_t>(i % WarpRecorder::kLanes));
    tracer.tally(f.x, f.y, call(f));
    if (i % WarpRecorder::kLanes == WarpRecorder::kLanes - 1 || i + 1 == fragments.size()) rec.end_warp();
  }
  return rec.counts();
}

// A per-pixel pass: 32 consecutive pixels of the row-major screen a warp.
template <class Pixel>
TrafficCounts replay_pixels(Extent screen, Pixel pixel) {
  WarpRecorder rec;
  const std::uint64_t n = std::uint64_t{screen.x} * screen.y;
  for (std::uint64_t i = 0; i < n; ++i) {
    rec.begin_lane(static_cast<std::uint32_t>(i % WarpRecorder::kLanes));
    pixel(static_cast<std::uint32_t>(i % screen.x), static_cast<std::uint32_t>(i / screen.x), rec);
    if (i % WarpRecorder::kLanes == WarpRecorder::kLanes - 1 || i + 1 == n) rec.end_warp();
  }
  return rec.counts();
}

template <class Word>
GpuTraffic model_ha(const TechniqueConfig& c, const OffsetSource& source, std::span<const Fragment> fragments) {
  const BufferConfig& b = c.buffer;
  const Extent table = b.table_or_screen();
  const std::uint32_t amax = (1u << b.age_bits) - 1u;
  const OffsetSequence offsets = source.make(table, amax);
  const MaxAgeTable cells(b.screen, b.block);
  std::vector<Word> slots(std::uint64_t{table.x} * table.y, Word{0});
  std::vector<std::uint32_t> max_age(std::uint64_t{cells.cells().x} * cells.cells().y, 0u);
  std::vector<std::uint32_t> saturation(b.saturation ? std::uint64_t{b.screen.x} * b.screen.y : 0u, 0u);
  KernelParams p;
  p.age_bits = b.age_bits;
  p.coverage_bits = b.record_layout().coverage_bits();
  p.payload_bits = b.layout == Layout::L64 ? 32 : 0;
  p.table = table;
  p.block = b.block;
  p.max_age_cells_x = cells.cells().x;
  p.iter_limit = b.iter_limit;
  p.cull_tau = b.early_cull_tau;
  p.screen = b.screen;
  p.saturation = b.saturation ? saturation.data() : nullptr;
  GpuTraffic t;
  WarpRecorder rec;
  traced::HashKernel<Word> k(p, offsets.values().data(), slots.data(), max_age.data(), rec);
  t.gather = replay_gather(fragments, rec, k, [&](const Fragment& f) {
    return k.ha_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
  });
  t.resolve = replay_pixels(b.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
    traced::HashKernel<Word> kr(p, offsets.values().data(), slots.data(), max_age.data(), r);
    (void)kr.ha_composite(glm::uvec2(x, y), glm::vec3(1.0f));
  });
  return t;
}

GpuTraffic model_lists(const TechniqueConfig& c, std::span<const Fragment> fragments) {
  const std::uint64_t pixels = std::uint64_t{c.buffer.screen.x} * c.buffer.screen.y;
  TechniqueConfig sized = c;
  if (sized.pool_capacity == 0) sized.pool_capacity = std::max<std::uint64_t>(fragments.size(), 1);
  const KernelUniforms u = kernel_uniforms(sized);
  std::vector<std::uint32_t> heads(pixels, 0u), next(sized.pool_capacity, 0u), saturation(pixels, 0u);
  std::vector<glm::uvec2> entries(sized.pool_capacity);
  const bool sorted = descriptor(c.technique).sorted_on_insert;
  GpuTraffic t;
  WarpRecorder rec;
  traced::ListsKernel k(u, heads.data(), entries.data(), next.data(), saturation.data(), rec);
  t.gather = replay_gather(fragments, rec, k, [&](const Fragment& f) {
    const glm::uvec2 p(f.x, f.y);
    return sorted ? k.sl_insert_fragment(p, f.depth, f.coverage, f.rgba) : k.ll_insert_fragment(p, f.depth, f.coverage, f.rgba);
  });
  if (!sorted)
    t.sort = replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
      traced::ListsKernel ks(u, heads.data(), entries.data(), next.data(), saturation.data(), r);
      (void)ks.ll_sort_pixel(glm::uvec2(x, y));
    });
  t.resolve = replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
    traced::ListsKernel kr(u, heads.data(), entries.data(), next.data(), saturation.data(), r);
    (void)kr.ll_composite(glm::uvec2(x, y), glm::vec3(1.0f));
  });
  return t;
}

GpuTraffic model_arrays(const TechniqueConfig& c, std::span<const Fragment> fragments) {
  const std::uint64_t pixels = std::uint64_t{c.buffer.screen.x} * c.buffer.screen.y;
  const KernelUniforms u = kernel_uniforms(c);
  std::vector<std::uint32_t> counts(pixels, 0u);
  std::vector<glm::uvec2> layers(pixels * c.layers);
  GpuTraffic t;
  WarpRecorder rec;
  traced::ArraysKernel k(u, counts.data(), layers.data(), rec);
  t.gather = replay_gather(fragments, rec, k, [&](const Fragment& f) {
    return k.fa_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
  });
  t.sort = replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
    traced::ArraysKernel ks(u, counts.data(), layers.data(), r);
    (void)ks.fa_sort_pixel(glm::uvec2(x, y));
  });
  t.resolve = replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
    traced::ArraysKernel kr(u, counts.data(), layers.data(), r);
    (void)kr.fa_composite(glm::uvec2(x, y), glm::vec3(1.0f));
  });
  return t;
}

// The k-buffer: with occupancy, the gather is three passes (kbuffer_entry.glsl's
// fill over the fragments, kb_count.comp.glsl's count per pixel, then the
// insertion), their counts summed; its layers stay sorted (no sort pass).
template <class Word>
GpuTraffic model_kbuffer(const TechniqueConfig& c, std::span<const Fragment> fragments) {
  const std::uint64_t pixels = std::uint64_t{c.buffer.screen.x} * c.buffer.screen.y;
  const KernelUniforms u = kernel_uniforms(c);
  std::vector<Word> slots(pixels * c.layers, Word{0});
  std::vector<std::uint32_t> occupancy(c.occupancy ? pixels * c.occupancy_words : 0u, 0u);
  std::vector<std::uint32_t> limits(c.occupancy ? pixels : 0u, 0u);
  GpuTraffic t;
  if (c.occupancy) {
    WarpRecorder fill;
    traced::KBufferKernel<Word> kf(u, slots.data(), occupancy.data(), limits.data(), fill);
    for (std::size_t i = 0; i < fragments.size(); ++i) {
      const Fragment& f = fragments[i];
      fill.begin_lane(static_cast<std::uint32_t>(i % WarpRecorder::kLanes));
      kf.kb_fill_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage);
      if (i % WarpRecorder::kLanes == WarpRecorder::kLanes - 1 || i + 1 == fragments.size()) fill.end_warp();
    }
    t.gather += fill.counts();
    t.gather += replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
      traced::KBufferKernel<Word> kc(u, slots.data(), occupancy.data(), limits.data(), r);
      kc.kb_count_pixel(glm::uvec2(x, y));
    });
    t.gather.lanes = 0;  // the fragments are counted once, by the insertion below
  }
  WarpRecorder rec;
  traced::KBufferKernel<Word> k(u, slots.data(), occupancy.data(), limits.data(), rec);
  t.gather += replay_gather(fragments, rec, k, [&](const Fragment& f) {
    return k.kb_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba);
  });
  t.resolve = replay_pixels(c.buffer.screen, [&](std::uint32_t x, std::uint32_t y, WarpRecorder& r) {
    traced::KBufferKernel<Word> kr(u, slots.data(), occupancy.data(), limits.data(), r);
    (void)kr.kb_composite(glm::uvec2(x, y), glm::vec3(1.0f));
  });
  return t;
}

}  // namespace

bool gpu_model_covers(Technique t) { return descriptor(t).traced_kernel != TracedKernel::None; }

GpuTraffic model_gpu_frame(const TechniqueConfig& c, const OffsetSource& offsets, std::span<const Fragment> fragments) {
  if (!gpu_model_covers(c.technique)) {
    std::string modelled;
    for (const TechniqueDescriptor* d : technique_registry())
      if (d->traced_kernel != TracedKernel::None) modelled += (modelled.empty() ? "" : ", ") + std::string(d->name);
    throw std::invalid_argument("the GPU traffic model has no traced kernel for technique " + to_string(c.technique) +
                                " (it models " + modelled + ")");
  }
  // Fragments off the screen are counted and never reach the technique (habuffer_insert).
  std::vector<Fragment> on_screen;
  on_screen.reserve(fragments.size());
  for (const Fragment& f : fragments)
    if (f.x < c.buffer.screen.x && f.y < c.buffer.screen.y) on_screen.push_back(f);
  // The descriptor says which kernel to trace; no technique is named here.
  switch (descriptor(c.technique).traced_kernel) {
    case TracedKernel::HashTable:
      return c.buffer.layout == Layout::L64 ? model_ha<std::uint64_t>(c, offsets, on_screen)
                                            : model_ha<std::uint32_t>(c, offsets, on_screen);
    case TracedKernel::PixelLayers:
      return model_arrays(c, on_screen);
    case TracedKernel::KBuffer:
      return c.buffer.layout == Layout::L64 ? model_kbuffer<std::uint64_t>(c, on_screen)
                                            : model_kbuffer<std::uint32_t>(c, on_screen);
    case TracedKernel::NodeLists:
      return model_lists(c, on_screen);
    case TracedKernel::None:
      break;
  }
  throw std::logic_error("unreachable: gpu_model_covers checked the traced kernel");
}

GpuCostModel GpuCostModel::h100() {
  GpuCostModel m;
  m.sector_ns = 32.0 / 3350.0;  // 32 bytes at HBM3's 3.35 TB/s
  // Fitted on docs/results/techniques-h100-512.json (scripts/gpu_model_check.py --fit 512x512): cold first
  // frames, so the per-pass constants hold allocation and first touch as well as launch and rasterization.
  m.gather_frame_ms = 8.13;
  m.gather_instruction_ns = 6.05;
  m.resolve_frame_ms = 0.574;
  m.resolve_instruction_ns = 1.05;
  m.source = "H100, fitted on its 512x512 round: gather 8.13 ms + 6.05 ns a warp memory instruction, "
             "resolve 0.574 ms + 1.05 ns a warp memory instruction; a priori: 32 B / 3.35 TB/s a sector";
  return m;
}

double GpuCostModel::gather_ms(const GpuTraffic& t) const {
  return gather_frame_ms + (gather_instruction_ns * static_cast<double>(t.gather.instructions) +
                            sector_ns * static_cast<double>(t.gather.sectors)) * 1e-6;
}

double GpuCostModel::resolve_ms(const GpuTraffic& t) const {
  const double instructions = static_cast<double>(t.sort.instructions + t.resolve.instructions);
  const double sectors = static_cast<double>(t.sort.sectors + t.resolve.sectors);
  return resolve_frame_ms + (resolve_instruction_ns * instructions + sector_ns * sectors) * 1e-6;
}

void set_gpu_model_columns(ResultRow& row, const GpuTraffic& t, const GpuCostModel& m) {
  const auto pass = [&](const char* name, const TrafficCounts& p) {
    const std::string n = std::string("model_") + name + "_";
    row.set(n + "instructions", p.instructions).set(n + "sectors", p.sectors).set(n + "lines", p.lines)
        .set(n + "atomics", p.atomics).set(n + "conflicts", p.conflicts).set(n + "chain", p.chain)
        .set(n + "chain_max", p.chain_max);
  };
  pass("gather", t.gather);
  pass("sort", t.sort);
  pass("resolve", t.resolve);
  const double gather = m.gather_ms(t), resolve = m.resolve_ms(t);
  row.set("model_gather_ms", gather).set("model_resolve_ms", resolve).set("model_total_ms", gather + resolve);
}

}  // namespace habuffer::harness
