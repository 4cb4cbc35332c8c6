// The two approximate baselines that store no lists: weighted blended OIT
// (McGuire and Bavoil 2013) and plain over-blending in submission order.
#include <string_view>

#include "habuffer/techniques/blended/blended_image.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::techniques {
namespace {

constexpr std::string_view kWboitOptions[] = {"depth-range"};

void validate(const TechniqueConfig&) {}

std::uint64_t wboit_memory_bytes(const TechniqueConfig& c, std::uint64_t) { return c.buffer.screen.area() * 20; }
std::uint64_t blend_memory_bytes(const TechniqueConfig& c, std::uint64_t) { return c.buffer.screen.area() * 16; }

// McGuire and Bavoil's RGBA32F + R32F targets; one RGBA32F target.
double wboit_paper_bytes(std::uint64_t pixels, std::uint64_t, double, std::uint32_t) {
  return 20.0 * static_cast<double>(pixels);
}
double blend_paper_bytes(std::uint64_t pixels, std::uint64_t, double, std::uint32_t) {
  return 16.0 * static_cast<double>(pixels);
}

std::unique_ptr<FragmentBuffer> make(const TechniqueConfig& c, const OffsetSource&) {
  return std::make_unique<BlendedImage>(c);
}

// They drop nothing, so nothing grows.
TechniqueConfig grown(const TechniqueConfig& c, const ResizePolicy&, const GrowthNeed&) { return c; }

constexpr std::string_view kBlendedHostShaders =
    "call `habuffer_insert` at most once per invocation and `discard` where it is not called with the invocation's own "
    "pixel (`habuffer_insert_here`; another pixel counts invalid), declaring no colour outputs of its own at locations 0 "
    "and 1 (the module's blend outputs; wboit uses both); draw into `gather_framebuffer()`, which the frame driver "
    "binds around the gather";

constexpr TechniqueDescriptor kWboit{
    .technique = Technique::Wboit,
    .name = "wboit",
    .summary = "weighted blended OIT (McGuire, Bavoil 2013): no lists, approximate",
    .properties =
        {
            .source = "baseline",
            .storage = "20 B/pixel (RGBA32F accum + revealage); the GPU adds a storage-buffer copy (40 B/pixel)",
            .bytes_per_fragment = "20 V / F",
            .passes = "gather (GPU: the fixed-function blender into the technique's framebuffer, in primitive "
                      "order); copy to storage buffers; resolve",
            .atomics_per_fragment = "none (the outcome tally's add only)",
            .sorted = "never: no lists (order-independent weights)",
            .exact_when = "never: approximate",
            .overflow = "none (`blended`)",
            .early_cull = "no",
            .host_shaders = kBlendedHostShaders,
        },
    .stores_lists = false,
    .exact = false,
    .early_cull = false,
    .sorted_on_insert = false,
    .reads_depth_range = true,
    .capacity = CapacityKind::None,
    .overflow_keeps_nearest = false,
    .paper_memory_row = "",
    .options = kWboitOptions,
    .lossless_hint = "",
    .validate = validate,
    .memory_bytes = wboit_memory_bytes,
    .paper_memory_bytes = wboit_paper_bytes,
    .make = make,
    .grown = grown,
};

// Plain blending: wboit's container and outputs without the weights; only
// what differs is stated.
constexpr TechniqueDescriptor kBlend = [] {
  TechniqueDescriptor d = kWboit;
  d.technique = Technique::Blend;
  d.name = "blend";
  d.summary = "unsorted over-blending in submission order: no lists, the floor of time";
  d.properties.storage = "16 B/pixel (RGBA32F); the GPU adds a storage-buffer copy (32 B/pixel)";
  d.properties.bytes_per_fragment = "16 V / F";
  d.properties.passes = "gather (GPU: the fixed-function blender, in primitive order); copy to storage buffers; resolve";
  d.properties.sorted = "never: no lists (submission order)";
  d.reads_depth_range = false;
  d.options = {};
  d.memory_bytes = blend_memory_bytes;
  d.paper_memory_bytes = blend_paper_bytes;
  return d;
}();

}  // namespace

namespace wboit {
const TechniqueDescriptor& descriptor() { return kWboit; }
}  // namespace wboit
namespace blend {
const TechniqueDescriptor& descriptor() { return kBlend; }
}  // namespace blend

}  // namespace habuffer::techniques
