// Per-pixel linked lists as two techniques: `lists` (seed 002, sorted after
// the gather) and `sorted-lists` (seed 001, kept sorted while inserting).
// They share the container (LinkedLists) and all but the insertion.
#include <stdexcept>
#include <string>
#include <string_view>

#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::techniques {
namespace {

std::uint64_t pool_memory_bytes(const TechniqueConfig& c, std::uint64_t capacity) {
  const std::uint64_t pixels = c.buffer.screen.area();
  const std::uint64_t saturation = c.buffer.saturation ? pixels * 4 : 0;  // a code per pixel
  return pixels * 4 + capacity * 12 + 4 + saturation;  // heads, (code, data, link) nodes, the node counter
}

double paper_pool_bytes(std::uint64_t pixels, std::uint64_t fragments, double, std::uint32_t) {
  return (32.0 * static_cast<double>(pixels) + 88.0 * static_cast<double>(fragments)) / 8.0;
}

std::unique_ptr<FragmentBuffer> make_lists(const TechniqueConfig& c, const OffsetSource&) {
  return std::make_unique<LinkedLists>(c);
}

constexpr std::string_view kListsOptions[] = {"pool", "lossless", "max-attempts"};
constexpr std::string_view kSortedListsOptions[] = {"pool",       "early-cull", "iter-limit",
                                                    "saturation", "lossless",   "max-attempts"};

constexpr TechniqueDescriptor kLists{
    .technique = Technique::Lists,
    .name = "lists",
    .summary = "per-pixel linked lists (Yang et al. 2010), sorted after the gather",
    .properties =
        {
            .source = "seed 002",
            .storage = "head image (4 B/pixel), node pool (12 B/node: code, data, link), one counter",
            .bytes_per_fragment = "12 + 4 V / F (pool at 80 % use: 15 + 4 V / F)",
            .passes = "gather; sort; resolve",
            .atomics_per_fragment = "one add (node counter), one exchange (head)",
            .sorted = "after the sort pass (insertion sort up to 32 entries in registers, in-place merge sort of "
                      "the list beyond)",
            .exact_when = "the pool holds the frame (auto pool: sized from a counting pass, grown at once, adapted "
                          "by SPEC 8's rule on its use)",
            .overflow = "`dropped_pool`, counted; `--lossless` regathers into a pool of the nodes asked for",
            .early_cull = "no",
            .host_shaders = "as `ha`",
        },
    .stores_lists = true,
    .exact = true,
    .early_cull = false,
    .sorted_on_insert = false,
    .reads_depth_range = false,
    .capacity = CapacityKind::PoolNodes,
    .overflow_keeps_nearest = false,
    .traced_kernel = TracedKernel::NodeLists,
    .paper_memory_row = "linked-list",
    .options = kListsOptions,
    .lossless_hint = "--lossless grows the node pool until they fit (or give a larger --pool)",
    .validate = validate_pool,
    .memory_bytes = pool_memory_bytes,
    .paper_memory_bytes = paper_pool_bytes,
    .make = make_lists,
    .grown = grown_pool,
};

// Sorted lists: the lists' container and pool, with the insertion that keeps
// each list sorted (and early termination); only what differs is stated.
constexpr TechniqueDescriptor kSortedLists = [] {
  TechniqueDescriptor d = kLists;
  d.technique = Technique::SortedLists;
  d.name = "sorted-lists";
  d.summary = "linked lists kept sorted by a lock-free insertion (guacamole's PreSortLF), early termination";
  d.properties = {
      .source = "seed 001",
      .storage = "as `lists` (+ 4 B/pixel saturation image with `--saturation on`)",
      .bytes_per_fragment = "as `lists`",
      .passes = "gather (lists sorted by insertion); resolve",
      .atomics_per_fragment = "one add (node), one 32-bit compare-and-swap per try",
      .sorted = "always, during insertion",
      .exact_when = "the pool holds the frame and no early termination",
      .overflow = "`dropped_pool`; `culled` / `saturated_rejected` with `--early-cull TAU [--saturation on]`",
      .early_cull = "`--early-cull TAU [--saturation on]`",
      .host_shaders = "as `lists`",
  };
  d.early_cull = true;
  d.sorted_on_insert = true;
  d.paper_memory_row = "";
  d.options = kSortedListsOptions;
  return d;
}();

}  // namespace

namespace lists {
const TechniqueDescriptor& descriptor() { return kLists; }
}  // namespace lists
namespace sorted_lists {
const TechniqueDescriptor& descriptor() { return kSortedLists; }
}  // namespace sorted_lists

}  // namespace habuffer::techniques
