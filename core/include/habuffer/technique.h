// The A-buffer techniques the library builds, and what fixes one besides the
// screen: the HA-buffer (its BufferConfig), per-pixel linked lists (a node
// pool) and fixed per-pixel arrays (K layers).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/resize_policy.h"

namespace habuffer {

enum class Technique {
  Ha,      // the coherent Robin Hood hash (SPEC): pointer-free, always sorted
  Lists,   // per-pixel linked lists (Yang et al. 2010), sorted after the gather
  Arrays,  // fixed per-pixel arrays of K layers (Crassin 2010), sorted after the gather
};

std::string to_string(Technique t);
// "ha", "lists", "arrays"; nullopt for anything else.
std::optional<Technique> parse_technique(std::string_view name);
// Every technique, in the order above.
std::vector<Technique> all_techniques();
// "ha, lists, arrays": for usage messages.
std::string technique_names();

struct TechniqueConfig {
  Technique technique = Technique::Ha;
  // Screen and record layout for every technique (the layout and age bits fix
  // the depth code, so lists of every technique compare bit for bit); table,
  // block, iteration limit and early cull are the HA-buffer's.
  BufferConfig buffer;
  std::uint64_t pool_capacity = 0;          // linked lists: nodes (at least 1)
  std::uint32_t layers = HA_DEFAULT_LAYERS;  // fixed arrays: K (at least 1)

  // Throws std::invalid_argument naming the field: the buffer's own rules,
  // early cull on a technique without it, a pool or layers of 0 or beyond
  // 32-bit node and slot indices.
  void validate() const;
  // Why this configuration cannot be built, or empty (validate's message).
  [[nodiscard]] std::string limit() const;

  // Lossless mode's next configuration after an attempt that dropped
  // fragments: the HA-buffer's table grown by `policy`; the lists' pool to
  // at least the nodes asked for (and one step); fixed arrays' K to the most
  // fragments a pixel received (and at least one more).
  [[nodiscard]] TechniqueConfig grown(const ResizePolicy& policy, std::uint64_t nodes_requested,
                                      std::uint32_t most_arrived) const;
};

// `config` as technique `t`, validated (throws as validate()).
TechniqueConfig validated_as(TechniqueConfig config, Technique t);

}  // namespace habuffer
