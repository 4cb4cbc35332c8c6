// The HA-buffer as a technique (seed 000): the coherent Robin Hood hash.
#include <stdexcept>
#include <string_view>

#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/offset_source.h"
#include "habuffer/max_age_table.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::techniques::ha {
namespace {

constexpr std::string_view kOptions[] = {"table",      "block",        "offsets",      "seed",     "early-cull",
                                         "iter-limit", "saturation",   "lossless",     "max-attempts", "insert-order",
                                         "dump-table", "dump-max-age"};

void validate(const TechniqueConfig&) {}  // BufferConfig::validate holds every rule of the table

std::uint64_t memory_bytes(const TechniqueConfig& c, std::uint64_t capacity) {
  const RecordLayout layout = c.buffer.record_layout();
  const Extent cells = MaxAgeTable(c.buffer.screen, c.buffer.block).cells();
  const std::uint64_t saturation = c.buffer.saturation ? c.buffer.screen.area() * 4 : 0;  // a code per pixel
  return capacity * layout.word_bytes() + cells.area() * 4 + std::uint64_t{layout.max_age()} * 8 + saturation;
}

double paper_memory_bytes(std::uint64_t pixels, std::uint64_t fragments, double load, std::uint32_t) {
  return (static_cast<double>(pixels) / 8.0 + 64.0 * static_cast<double>(fragments) / load) / 8.0;
}

std::unique_ptr<FragmentBuffer> make(const TechniqueConfig& c, const OffsetSource& offsets) {
  c.validate();  // before the offsets are made for its table
  const Extent table = c.buffer.table_or_screen();
  return std::make_unique<HaBuffer>(c.buffer, offsets.make(table, c.buffer.record_layout().max_age()));
}

TechniqueConfig grown(const TechniqueConfig& c, const ResizePolicy& policy, const GrowthNeed& need) {
  TechniqueConfig next = c;
  next.buffer.table = policy.grown(c.buffer.table_or_screen(), c.buffer.screen, need.records);
  return next;
}

constexpr TechniqueDescriptor kDescriptor{
    .technique = Technique::Ha,
    .name = "ha",
    .summary = "the coherent Robin Hood hash (SPEC): pointer-free, always sorted",
    .properties =
        {
            .source = "seed 000",
            .storage = "table of H slots, one 64-bit (L64) or 32-bit (L32) record each, max-age table "
                       "(4 bytes per 8x8 block), offsets",
            .bytes_per_fragment = "8 / load (L64; 4 / load for L32), + 0.5 / load lock words on emulated64",
            .passes = "gather; resolve (the clear pass of the next frame counts the records)",
            .atomics_per_fragment = "one atomicMax per probe that can win (plain loads for probes that cannot), "
                                    "about 6.5 on `hairball`; emulated64: a lock per such probe",
            .sorted = "always, during insertion",
            .exact_when = "no fragment fails (lossless mode grows the table; failures need more age bits beyond "
                          "AMAX records per pixel)",
            .overflow = "`failed_age` / `failed_iter`, counted; `--lossless` grows the table",
            .early_cull = "`--early-cull TAU [--saturation on]`",
            .host_shaders = "call `habuffer_insert` any number of times per invocation, for any pixel",
        },
    .stores_lists = true,
    .exact = true,
    .early_cull = true,
    .sorted_on_insert = true,
    .reads_depth_range = false,
    .capacity = CapacityKind::TableSlots,
    .overflow_keeps_nearest = false,
    .traced_kernel = TracedKernel::HashTable,
    .paper_memory_row = "",
    .options = kOptions,
    .lossless_hint = "--lossless grows the table until they fit (or give a larger --table, more --age-bits)",
    .validate = validate,
    .memory_bytes = memory_bytes,
    .paper_memory_bytes = paper_memory_bytes,
    .make = make,
    .grown = grown,
};

}  // namespace

const TechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::techniques::ha
