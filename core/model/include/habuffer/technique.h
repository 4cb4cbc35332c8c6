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
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique_list.h"

namespace habuffer {

/// The techniques the library builds, one enumerator per line of
/// technique_list.h, in its order; what each is and has is its descriptor
/// (technique_descriptor.h).
enum class Technique {
#define HABUFFER_TECHNIQUE_ENUMERATOR(Enumerator, ns) Enumerator,
  HABUFFER_TECHNIQUES(HABUFFER_TECHNIQUE_ENUMERATOR)
#undef HABUFFER_TECHNIQUE_ENUMERATOR
};

/// How many techniques technique_list.h registers.
#define HABUFFER_COUNT_TECHNIQUE(Enumerator, ns) +1
inline constexpr std::size_t kTechniqueCount = 0 HABUFFER_TECHNIQUES(HABUFFER_COUNT_TECHNIQUE);
#undef HABUFFER_COUNT_TECHNIQUE

/// A registry's check (the CPU's and the GPU's): throws std::logic_error
/// naming `registry` when a descriptor is not at its enumerator's place.
template <class Descriptor>
void check_registry_order(std::span<const Descriptor* const> list, std::string_view registry) {
  for (std::size_t i = 0; i < list.size(); ++i)
    if (static_cast<std::size_t>(list[i]->technique) != i)
      throw std::logic_error(std::string(registry) + ": the descriptor at place " + std::to_string(i) +
                             " is not its enumerator's in technique_list.h");
}

/// The technique's name, as parse_technique reads it.
std::string to_string(Technique t);
/// The technique named `name` (a registered descriptor's name); nullopt for anything else.
std::optional<Technique> parse_technique(std::string_view name);
/// Every technique, in the order above.
std::vector<Technique> all_techniques();
/// "ha, lists, ...": for usage messages.
std::string technique_names();

/// What a technique has (the options and counters that apply to it), read
/// from its descriptor (technique_descriptor.h).
bool stores_lists(Technique t);     ///< per-pixel lists one can read (not the blended baselines)
bool exact_technique(Technique t);  ///< lists equal the HA-buffer's when nothing is dropped or culled
bool uses_pool(Technique t);        ///< its capacity is a node pool (CapacityKind::PoolNodes)
bool uses_layers(Technique t);      ///< its capacity is K layers per pixel (CapacityKind::PixelLayers)
bool uses_table(Technique t);       ///< its capacity is a hash table of slots (ha)

/// The depth interval the scene's fragments lie in (window depth t): the
/// k-buffer's occupancy buckets divide it, wboit's weight is normalized to
/// it. Fragments outside still count (clamped to the nearest end).
struct DepthRange {
  float near_t = 0.0f;  ///< the nearest end, in [0, far_t)
  float far_t = 1.0f;  ///< the farthest end, at most 1
  /// Memberwise equality.
  friend bool operator==(const DepthRange&, const DepthRange&) = default;
};

/// What a container's last insert asked for beyond what it held: lossless
/// mode's next size is computed from it (FragmentBuffer::growth_need()).
struct GrowthNeed {
  std::uint64_t nodes_requested = 0;  ///< pool techniques: the nodes the batch asked for
  std::uint32_t most_arrived = 0;     ///< per-pixel techniques: the most fragments a pixel received
  /// Records the attempt asked to keep: stored plus failed
  /// (Counters::records_needed); the HA-buffer's table is sized for them.
  std::uint64_t records = 0;
  /// The count `t`'s container is sized by (lossless growth, adaptive
  /// sizing, BuildAttempt::sized_for): a pool technique's nodes asked for,
  /// any other's records.
  [[nodiscard]] std::uint64_t count_for(Technique t) const;
};

/// Which technique, and the parameters only some techniques read: declared
/// once here, and held (as a base) by TechniqueConfig, by render's
/// RenderSettings and by the CLI's options, so no struct restates them and
/// none copies them field by field. Which of them a technique reads is its
/// descriptor's (technique_descriptor.h; TechniqueConfig::relevant()).
struct TechniqueChoice {
  Technique technique = Technique::Ha;  ///< which container
  /// Pool techniques: nodes; 0: automatic (build_technique, the GL
  /// containers and render size it from the fragments).
  std::uint64_t pool_capacity = 0;
  std::uint32_t layers = HABUFFER_DEFAULT_LAYERS;  ///< techniques of K layers per pixel: K (at least 1)
  /// k-buffer: occupancy-map culling (a fill pass, a count pass, then
  /// insertion rejecting what lies beyond the k-th occupied bucket) with
  /// 32 * occupancy_words buckets per pixel over depth_range.
  bool occupancy = false;
  std::uint32_t occupancy_words = HABUFFER_DEFAULT_OCCUPANCY_WORDS;  ///< k-buffer: 32-bit occupancy words per pixel
  DepthRange depth_range;  ///< k-buffer's occupancy, wboit's weights
  /// Memberwise equality.
  friend bool operator==(const TechniqueChoice&, const TechniqueChoice&) = default;
};

/// Everything that fixes one technique's container besides the HA-buffer's
/// offsets: the choice, and the screen and record layout every technique
/// shares (the layout and age bits fix the depth code, so lists of every
/// technique compare bit for bit) with the HA-buffer's table, block,
/// iteration limit and early cull.
struct TechniqueConfig : TechniqueChoice {
  BufferConfig buffer;  ///< screen, layout, age bits; the HA-buffer's table and early cull

  /// Throws std::invalid_argument naming the field: the buffer's own rules,
  /// early cull on a technique without it, a pool or layers of 0 or beyond
  /// 32-bit node and slot indices.
  void validate() const;
  /// Why this configuration cannot be built, or empty (validate's message).
  [[nodiscard]] std::string limit() const;

  /// Memberwise equality (the choice and the buffer).
  friend bool operator==(const TechniqueConfig&, const TechniqueConfig&) = default;

  /// Lossless mode's next configuration after an attempt that dropped
  /// fragments (the descriptor's rule), from what the attempt asked for:
  /// the HA-buffer's table for need.records by `policy`
  /// (ResizePolicy::grown: at the middle of the band in one step under the
  /// count rule); a pool for the nodes asked for (likewise); fixed arrays'
  /// K to the most fragments a pixel received (and at least one more); the
  /// k-buffer's K doubled.
  [[nodiscard]] TechniqueConfig grown(const ResizePolicy& policy, const GrowthNeed& need) const;
  /// An automatic container's first size for a frame of `fragments`
  /// fragments (the counting pass, SPEC 8): the HA-buffer's table at the
  /// middle of `policy`'s band of loads (ResizePolicy::initial_table), a
  /// pool at its grow_at use (ResizePolicy::automatic); K and the other
  /// fields as they are. Both paths, `render` and the GL frame driver size
  /// from it. Throws std::invalid_argument beyond 2^32 - 1 slots.
  [[nodiscard]] TechniqueConfig sized_for(const ResizePolicy& policy, std::uint64_t fragments) const;
  /// This configuration with the choice's fields its technique does not
  /// read at their defaults: configurations whose relevant() parts are equal
  /// make the same container (the buffer's fields are compared as they are).
  [[nodiscard]] TechniqueConfig relevant() const;
  /// The capacity this configuration asks for: the HA-buffer's table slots,
  /// the pool's nodes, K times the pixels, or 0 for the baselines.
  [[nodiscard]] std::uint64_t configured_capacity() const;
};

/// The HA-buffer of `buffer` as a technique configuration.
TechniqueConfig ha_technique_config(const BufferConfig& buffer);

/// The rules shared by the pool techniques: a pool of 1 to 2^32 - 2 nodes
/// (links are 32-bit node numbers with 0 for "none"); throws std::invalid_argument.
void validate_pool(const TechniqueConfig& config);
/// Lossless growth of a pool technique: the pool to at least the nodes the
/// attempt asked for, and one step of `policy`.
TechniqueConfig grown_pool(const TechniqueConfig& config, const ResizePolicy& policy, const GrowthNeed& need);

/// The rules shared by the techniques of K layers per pixel: K at least 1,
/// and K times the pixels at most 2^32 - 1 slots (throws std::invalid_argument).
void validate_layers(const TechniqueConfig& config);

/// `config`, validated (throws as validate()) as technique `t`; throws
/// std::invalid_argument when it configures another technique.
TechniqueConfig validated_as(TechniqueConfig config, Technique t);

}  // namespace habuffer
