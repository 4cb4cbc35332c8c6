/// @file
/// A technique as one unit: everything the library, the harness and the CLI
/// need to know about a technique, declared once in the technique's folder
/// (techniques/NAME/cpu/) and listed by the registry
/// (technique_registry(), below). Code outside the folders asks the descriptor, never
/// "which technique is this": no switch over Technique, no dynamic_cast to a
/// container. The GPU path's half is habuffer/gl/technique_registry.h's
/// GlTechniqueDescriptor, in the technique's gl folder.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "habuffer/technique.h"

namespace habuffer {

class FragmentBuffer;
struct OffsetSource;
struct ResizePolicy;

/// What a technique's capacity counts, and so what automatic sizing (SPEC 8's
/// 80/30 rule) and lossless mode grow.
enum class CapacityKind {
  None,         ///< nothing to size: the baselines blend every fragment
  TableSlots,   ///< a hash table of H slots (capacity: slots)
  PoolNodes,    ///< one node pool shared by all pixels (capacity: nodes)
  PixelLayers,  ///< K records per pixel (capacity: K times the pixels)
};

/// The kernel the harness's GPU traffic model (harness/gpu_model.h) traces a
/// technique's frame with: its own kernel, instrumented.
enum class TracedKernel {
  None,         ///< not modelled
  HashTable,    ///< the HA-buffer's probe, insert and traversal
  NodeLists,    ///< per-pixel node lists (unsorted or kept sorted)
  PixelLayers,  ///< fixed per-pixel arrays
  KBuffer,      ///< the k-buffer
};

/// The README property table's rows for one technique, as data: the table is
/// written from these (`habuffer techniques --markdown`), and
/// tests/test_technique_registry.cpp checks that the README is current and
/// that the claims hold on a stream (exactness, sortedness, memory).
struct TechniqueProperties {
  std::string_view source;                ///< the paper it implements ("seed 000") or "baseline"
  std::string_view storage;               ///< the buffers it allocates
  std::string_view bytes_per_fragment;    ///< bytes per stored fragment by the memory model
  std::string_view passes;                ///< the passes of a frame
  std::string_view atomics_per_fragment;  ///< atomic operations per fragment on the GPU
  std::string_view sorted;                ///< when its lists are sorted
  std::string_view exact_when;            ///< when its lists equal the HA-buffer's
  std::string_view overflow;              ///< what it does when full, and the counters that say so
  std::string_view early_cull;            ///< its early cull, or "no"
  std::string_view host_shaders;          ///< what a host shader calling habuffer_insert must know
};

/// One technique (see above). Descriptors are constants with static storage,
/// made by the technique's folder and listed by the registry.
struct TechniqueDescriptor {
  Technique technique;            ///< its enumerator (technique_list.h)
  std::string_view name;          ///< as --technique and the harness' words spell it
  std::string_view summary;       ///< one line: what it is
  TechniqueProperties properties;  ///< the README's property table column
  bool stores_lists = true;       ///< per-pixel lists one can read (the baselines store none)
  bool exact = true;              ///< its lists equal the HA-buffer's when nothing is dropped or culled
  bool early_cull = false;        ///< --early-cull TAU, --saturation and the iteration limit apply
  bool sorted_on_insert = false;  ///< lists are kept sorted while inserting (no sort pass)
  bool reads_depth_range = false;  ///< its configuration's DepthRange matters
  CapacityKind capacity = CapacityKind::None;  ///< what its capacity counts (and what grows)
  /// Per-pixel layers full: the K nearest stay (true), or the first K to
  /// arrive (false). Only for CapacityKind::PixelLayers.
  bool overflow_keeps_nearest = false;
  /// The kernel the GPU traffic model traces for it (None: not modelled).
  TracedKernel traced_kernel = TracedKernel::None;
  /// Its row in seed 000's Table 1 of published sizes ("linked-list"), or
  /// "" where the harness' label names it.
  std::string_view paper_memory_row;
  /// The CLI options only some techniques take that this one takes
  /// ("table", "pool", "layers", ...): the CLI refuses any other technique's.
  /// Those that set a configuration field are rows of the technique option
  /// table (habuffer/technique_options.h); this is the technique's view of it.
  std::span<const std::string_view> options;
  /// What --lossless does for it, for the warning a lossy run prints ("" when
  /// it drops nothing).
  std::string_view lossless_hint;
  /// Throws std::invalid_argument naming the field for what is wrong with
  /// `config` for this technique beyond the common rules
  /// (TechniqueConfig::validate has checked the screen and record layout).
  void (*validate)(const TechniqueConfig& config);
  /// Bytes of every buffer the CPU container allocates with `capacity`
  /// records (slots, nodes or the layers of every pixel), to the byte.
  std::uint64_t (*memory_bytes)(const TechniqueConfig& config, std::uint64_t capacity);
  /// Seed 000 Table 1's formula (bits per pixel and per fragment, over 8), or
  /// its analogue for techniques the paper does not list.
  double (*paper_memory_bytes)(std::uint64_t pixels, std::uint64_t fragments, double load, std::uint32_t layers);
  /// The CPU container for a validated `config`.
  std::unique_ptr<FragmentBuffer> (*make)(const TechniqueConfig& config, const OffsetSource& offsets);
  /// Lossless mode's next configuration after an attempt that dropped
  /// fragments, by `policy` and what the attempt asked for.
  TechniqueConfig (*grown)(const TechniqueConfig& config, const ResizePolicy& policy, const GrowthNeed& need);

  /// Whether it takes the CLI option `name` (one of `options`).
  [[nodiscard]] bool takes(std::string_view option) const;
  /// Whether a configuration of 0 capacity means "size it automatically".
  [[nodiscard]] bool sized_automatically() const {
    return capacity == CapacityKind::TableSlots || capacity == CapacityKind::PoolNodes;
  }
};

/// One field of a technique's configuration in a report (stats JSON).
struct ReportField {
  std::string_view name;  ///< the JSON key: "layers", "pool_nodes", "occupancy", ...
  std::variant<std::uint64_t, bool, DepthRange> value;  ///< its value
};
/// The configuration fields `config`'s technique reports: the JSON keys of
/// the technique option table's rows (habuffer/technique_options.h) whose
/// option it takes, in the table's order, a row that needs another only when
/// that one is on: "layers" (K: `capacity` over the pixels), "pool_nodes"
/// (`capacity`), "occupancy" and, when on, "occupancy_words", "depth_range".
std::vector<ReportField> technique_report_fields(const TechniqueConfig& config, std::uint64_t capacity);

/// The descriptor of `t` (every enumerator has one).
const TechniqueDescriptor& descriptor(Technique t);

/// What a loss warning ends with for technique `t` (empty where it drops
/// nothing): its lossless_hint and, where which fragments drop depends on
/// the order they arrive in (every technique that stores lists but keeps
/// the K nearest), that the lossy lists then differ between paths, thread
/// counts and insert orders: only a lossless result is bit-identical across
/// them (docs/spec-notes.md, "Which results are bit-identical").
std::string loss_hint(Technique t);
/// Every descriptor, in technique_list.h's order.
std::span<const TechniqueDescriptor* const> technique_registry();
/// The descriptor named `name`; nullptr for anything else.
const TechniqueDescriptor* find_technique(std::string_view name);
/// Every technique that takes `option`, as "ha, sorted-lists": for messages.
std::string techniques_taking(std::string_view option);
/// The README's property table (markdown), written from the descriptors,
/// `per_table` techniques side by side.
std::string property_table_markdown(std::size_t per_table = 3);

}  // namespace habuffer
