/// @file
/// The techniques the library builds, and what fixes one besides the screen:
/// the HA-buffer (its BufferConfig), per-pixel linked lists sorted after the
/// gather or kept sorted while inserting (a node pool), fixed per-pixel arrays
/// and the k-buffer (K layers, the k-buffer's optional occupancy map), and the
/// two approximate baselines that store no lists (weighted blended OIT, plain
/// blending).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/resize_policy.h"

namespace habuffer {

/// The techniques the library builds (see above).
enum class Technique {
  Ha,      ///< the coherent Robin Hood hash (SPEC): pointer-free, always sorted
  Lists,   ///< per-pixel linked lists (Yang et al. 2010), sorted after the gather
  Arrays,  ///< fixed per-pixel arrays of K layers (Crassin 2010), sorted after the gather
  SortedLists,  ///< linked lists kept sorted by a lock-free insertion (guacamole's PreSortLF), early termination
  KBuffer,      ///< the k nearest fragments per pixel by atomic max (Vasilakis 2015), occupancy-map culling
  Wboit,        ///< weighted blended OIT (McGuire, Bavoil 2013): no lists, approximate
  Blend,        ///< unsorted over-blending in submission order: no lists, the floor of time
};

/// The technique's name, as parse_technique reads it.
std::string to_string(Technique t);
/// "ha", "lists", "arrays", "sorted-lists", "kbuffer", "wboit", "blend"; nullopt for anything else.
std::optional<Technique> parse_technique(std::string_view name);
/// Every technique, in the order above.
std::vector<Technique> all_techniques();
/// "ha, lists, ...": for usage messages.
std::string technique_names();

/// What a technique has (the options and counters that apply to it).
bool stores_lists(Technique t);     ///< per-pixel lists one can read (not wboit, blend)
bool exact_technique(Technique t);  ///< lists equal the HA-buffer's when nothing is dropped or culled
bool has_early_cull(Technique t);   ///< ha, sorted-lists
bool uses_pool(Technique t);        ///< lists, sorted-lists
bool uses_layers(Technique t);      ///< arrays, kbuffer
/// The linked-list container's technique for `t`: sorted-lists stays, anything else is lists.
Technique lists_flavour(Technique t);

/// The depth interval the scene's fragments lie in (window depth t): the
/// k-buffer's occupancy buckets divide it, wboit's weight is normalized to
/// it. Fragments outside still count (clamped to the nearest end).
struct DepthRange {
  float near_t = 0.0f;  ///< the nearest end, in [0, far_t)
  float far_t = 1.0f;  ///< the farthest end, at most 1
  /// Memberwise equality.
  friend bool operator==(const DepthRange&, const DepthRange&) = default;
};

/// Everything that fixes one technique's container besides the HA-buffer's offsets.
struct TechniqueConfig {
  Technique technique = Technique::Ha;  ///< which container
  /// Screen and record layout for every technique (the layout and age bits fix
  /// the depth code, so lists of every technique compare bit for bit); table,
  /// block, iteration limit and early cull are the HA-buffer's.
  BufferConfig buffer;
  std::uint64_t pool_capacity = 0;          ///< linked lists, sorted lists: nodes; 0: automatic (build_technique, GL containers)
  std::uint32_t layers = HABUFFER_DEFAULT_LAYERS;  ///< fixed arrays, k-buffer: K (at least 1)
  /// k-buffer: occupancy-map culling (a fill pass, a count pass, then
  /// insertion rejecting what lies beyond the k-th occupied bucket) with
  /// 32 * occupancy_words buckets per pixel over depth_range.
  bool occupancy = false;
  std::uint32_t occupancy_words = HABUFFER_DEFAULT_OCCUPANCY_WORDS;  ///< k-buffer: 32-bit occupancy words per pixel
  DepthRange depth_range;  ///< k-buffer's occupancy, wboit's weights

  /// Throws std::invalid_argument naming the field: the buffer's own rules,
  /// early cull on a technique without it, a pool or layers of 0 or beyond
  /// 32-bit node and slot indices.
  void validate() const;
  /// Why this configuration cannot be built, or empty (validate's message).
  [[nodiscard]] std::string limit() const;

  /// Lossless mode's next configuration after an attempt that dropped
  /// fragments: the HA-buffer's table grown by `policy`; the lists' pool to
  /// at least the nodes asked for (and one step); fixed arrays' K to the most
  /// fragments a pixel received (and at least one more).
  /// Memberwise equality.
  friend bool operator==(const TechniqueConfig&, const TechniqueConfig&) = default;

  [[nodiscard]] TechniqueConfig grown(const ResizePolicy& policy, std::uint64_t nodes_requested,
                                      std::uint32_t most_arrived) const;
};

/// The HA-buffer of `buffer` as a technique configuration.
TechniqueConfig ha_technique_config(const BufferConfig& buffer);

/// `config`, validated (throws as validate()) as technique `t`; throws
/// std::invalid_argument when it configures another technique.
TechniqueConfig validated_as(TechniqueConfig config, Technique t);

}  // namespace habuffer
