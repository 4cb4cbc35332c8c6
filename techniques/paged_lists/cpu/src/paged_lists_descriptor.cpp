// Paged per-pixel lists (seed 000's "paged lists", Table 1 and 2): linked
// lists whose nodes come in pages of K = 4 per pixel, sorted after the
// gather as `lists` are.
#include <stdexcept>
#include <string>
#include <string_view>

#include "habuffer/memory_model.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"

namespace habuffer::techniques {
namespace {

std::uint64_t pool_memory_bytes(const TechniqueConfig& c, std::uint64_t capacity) {
  // heads, (code, data, link) nodes, the node counter and the wasted-page count
  return c.buffer.screen.area() * 4 + capacity * 12 + 4 + 4;
}

double paper_bytes(std::uint64_t pixels, std::uint64_t fragments, double, std::uint32_t) {
  return paper_paged_lists_bytes(pixels, fragments, kPagedListsPageNodes);
}

std::unique_ptr<FragmentBuffer> make(const TechniqueConfig& c, const OffsetSource&) {
  return std::make_unique<PagedLists>(c);
}

constexpr std::string_view kOptions[] = {"pool", "iter-limit", "lossless", "max-attempts"};

constexpr TechniqueDescriptor kPagedLists{
    .technique = Technique::PagedLists,
    .name = "paged-lists",
    .summary = "per-pixel linked lists with nodes in pages of 4 per pixel, sorted after the gather",
    .properties =
        {
            .source = "seed 000, Table 1",
            .storage = "head image (4 B/pixel), node pool (12 B/node: code, data, link) taken in pages of 4 nodes "
                       "per pixel, two counters (nodes, wasted pages); the paper's 40V + F/K (56K + 32) bits has a "
                       "link per page and an 8-bit count per pixel instead of a link per node",
            .bytes_per_fragment = "12 + 4 V / F, plus up to 3 unused nodes (36 B) per pixel in its last page",
            .passes = "gather; sort; resolve",
            .atomics_per_fragment = "one 32-bit compare-and-swap (head) per try, one add (page counter) per 4",
            .sorted = "after the sort pass (as `lists`)",
            .exact_when = "the pool holds the frame's pages: one thread asks a page per 4 fragments of a pixel, racing "
                          "invocations may lose some, never more than a page per fragment (auto pool and lossless: "
                          "grown to the nodes asked for)",
            .overflow = "`dropped_pool` when a pixel's page is full and no page is left; `failed_iter` beyond the "
                        "iteration limit (default 65536 tries); `--lossless` regathers into a pool of the nodes asked "
                        "for",
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
    .paper_memory_row = "",
    .options = kOptions,
    .lossless_hint = "--lossless grows the node pool until they fit (or give a larger --pool)",
    .validate = validate_pool,
    .memory_bytes = pool_memory_bytes,
    .paper_memory_bytes = paper_bytes,
    .make = make,
    .grown = grown_pool,
};

}  // namespace

namespace paged_lists {
const TechniqueDescriptor& descriptor() { return kPagedLists; }
}  // namespace paged_lists

}  // namespace habuffer::techniques
