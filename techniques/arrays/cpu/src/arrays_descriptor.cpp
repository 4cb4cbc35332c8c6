// Fixed per-pixel arrays of K layers (seed 004, Crassin 2010), sorted after
// the gather.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::techniques::arrays {
namespace {

constexpr std::string_view kOptions[] = {"layers", "lossless", "max-attempts"};

void validate(const TechniqueConfig& c) { validate_layers(c); }

std::uint64_t memory_bytes(const TechniqueConfig& c, std::uint64_t) {
  const std::uint64_t pixels = c.buffer.screen.area();
  return pixels * 4 + std::uint64_t{c.layers} * pixels * 8 + 4;  // counters, (code, data) layers, overflow note
}

double paper_memory_bytes(std::uint64_t pixels, std::uint64_t, double, std::uint32_t layers) {
  const double v = static_cast<double>(pixels);
  return (32.0 * v + 56.0 * static_cast<double>(layers) * v) / 8.0;
}

std::unique_ptr<FragmentBuffer> make(const TechniqueConfig& c, const OffsetSource&) {
  return std::make_unique<FixedArrays>(c);
}

TechniqueConfig grown(const TechniqueConfig& c, const ResizePolicy&, const GrowthNeed& need) {
  TechniqueConfig next = c;
  next.layers = std::max(need.most_arrived, c.layers + 1);
  return next;
}

constexpr TechniqueDescriptor kDescriptor{
    .technique = Technique::Arrays,
    .name = "arrays",
    .summary = "fixed per-pixel arrays of K layers (Crassin 2010), sorted after the gather",
    .properties =
        {
            .source = "seed 004",
            .storage = "a counter per pixel (4 B) and K layers per pixel (8 B each)",
            .bytes_per_fragment = "8 K V / F + 4 V / F",
            .passes = "gather; sort; resolve",
            .atomics_per_fragment = "one add (pixel counter)",
            .sorted = "after the sort pass (insertion sort up to 32, heap sort in place beyond)",
            .exact_when = "K is at least the depth complexity",
            .overflow = "`dropped_layers`, counted; which K of a pixel stay depends on arrival order; `--lossless` "
                        "raises K to the deepest pixel",
            .early_cull = "no",
            .host_shaders = "as `ha`",
        },
    .stores_lists = true,
    .exact = true,
    .early_cull = false,
    .sorted_on_insert = false,
    .reads_depth_range = false,
    .capacity = CapacityKind::PixelLayers,
    .overflow_keeps_nearest = false,
    .traced_kernel = TracedKernel::PixelLayers,
    .paper_memory_row = "",
    .options = kOptions,
    .lossless_hint = "--lossless raises K to the deepest pixel (or give more --layers)",
    .validate = validate,
    .memory_bytes = memory_bytes,
    .paper_memory_bytes = paper_memory_bytes,
    .make = make,
    .grown = grown,
};

}  // namespace

const TechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::techniques::arrays
