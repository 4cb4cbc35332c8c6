// The k-buffer (seed 003, Vasilakis 2015): the K nearest fragments per pixel
// by atomic max, with occupancy-map culling.
#include <stdexcept>
#include <string>
#include <string_view>

#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::techniques::kbuffer {
namespace {

constexpr std::string_view kOptions[] = {"layers", "occupancy", "occupancy-words", "depth-range", "lossless",
                                         "max-attempts"};

void validate(const TechniqueConfig& c) {
  validate_layers(c);
  if (c.occupancy && std::uint64_t{c.occupancy_words} * c.buffer.screen.area() > UINT32_MAX)
    throw std::invalid_argument(std::to_string(c.occupancy_words) + " occupancy words of screen " +
                                c.buffer.screen.str() + " exceed 2^32 - 1 words");
}

std::uint64_t memory_bytes(const TechniqueConfig& c, std::uint64_t) {
  const std::uint64_t pixels = c.buffer.screen.area();
  const std::uint64_t occupancy = c.occupancy ? pixels * (std::uint64_t{c.occupancy_words} + 1) * 4 : 0;
  return std::uint64_t{c.layers} * pixels * c.buffer.record_layout().word_bytes() + occupancy;
}

// Not in seed 000's table: the arrays' records without their counter.
double paper_memory_bytes(std::uint64_t pixels, std::uint64_t, double, std::uint32_t layers) {
  return 56.0 * static_cast<double>(layers) * static_cast<double>(pixels) / 8.0;
}

std::unique_ptr<FragmentBuffer> make(const TechniqueConfig& c, const OffsetSource&) {
  return std::make_unique<KBuffer>(c);
}

// The k-buffer does not know how deep its pixels were: it doubles K.
TechniqueConfig grown(const TechniqueConfig& c, const ResizePolicy&, const GrowthNeed&) {
  TechniqueConfig next = c;
  next.layers = c.layers * 2;
  return next;
}

constexpr TechniqueDescriptor kDescriptor{
    .technique = Technique::KBuffer,
    .name = "kbuffer",
    .summary = "the k nearest fragments per pixel by atomic max (Vasilakis 2015), occupancy-map culling",
    .properties =
        {
            .source = "seed 003",
            .storage = "K records per pixel (8 B L64, 4 B L32); occupancy map (4 D + 4 B/pixel) with "
                       "`--occupancy on`",
            .bytes_per_fragment = "K V (8 L64, 4 L32) / F",
            .passes = "gather (with occupancy: fill pass, count pass, gather); resolve",
            .atomics_per_fragment = "one atomicMax per layer that can win (emulated64: a lock)",
            .sorted = "always, during insertion",
            .exact_when = "K is at least the depth complexity (else exactly the K nearest)",
            .overflow = "`dropped_layers`, `occupancy_rejected`",
            .early_cull = "no (occupancy culling keeps the K nearest exactly)",
            .host_shaders = "as `ha`",
        },
    .stores_lists = true,
    .exact = true,
    .early_cull = false,
    .sorted_on_insert = true,
    .reads_depth_range = true,
    .capacity = CapacityKind::PixelLayers,
    .overflow_keeps_nearest = true,
    .traced_kernel = TracedKernel::KBuffer,
    .paper_memory_row = "",
    .options = kOptions,
    .lossless_hint = "the k-buffer keeps the K nearest by design: --lossless doubles K until nothing drops",
    .validate = validate,
    .memory_bytes = memory_bytes,
    .paper_memory_bytes = paper_memory_bytes,
    .make = make,
    .grown = grown,
};

}  // namespace

const TechniqueDescriptor& descriptor() { return kDescriptor; }

}  // namespace habuffer::techniques::kbuffer
