#include "habuffer/technique.h"

#include <algorithm>
#include <stdexcept>

#include "habuffer/technique_params.h"

namespace habuffer {

std::string to_string(Technique t) {
  switch (t) {
    case Technique::Ha: return "ha";
    case Technique::Lists: return "lists";
    case Technique::Arrays: return "arrays";
    case Technique::SortedLists: return "sorted-lists";
    case Technique::KBuffer: return "kbuffer";
    case Technique::Wboit: return "wboit";
    case Technique::Blend: return "blend";
  }
  return "?";
}

std::optional<Technique> parse_technique(std::string_view name) {
  for (Technique t : all_techniques())
    if (name == to_string(t)) return t;
  return std::nullopt;
}

std::vector<Technique> all_techniques() {
  return {Technique::Ha,      Technique::Lists, Technique::Arrays, Technique::SortedLists,
          Technique::KBuffer, Technique::Wboit, Technique::Blend};
}

bool stores_lists(Technique t) { return t != Technique::Wboit && t != Technique::Blend; }
bool exact_technique(Technique t) { return stores_lists(t); }
bool has_early_cull(Technique t) { return t == Technique::Ha || t == Technique::SortedLists; }
bool uses_pool(Technique t) { return t == Technique::Lists || t == Technique::SortedLists; }
bool uses_layers(Technique t) { return t == Technique::Arrays || t == Technique::KBuffer; }
Technique lists_flavour(Technique t) { return t == Technique::SortedLists ? t : Technique::Lists; }

std::string technique_names() {
  std::string s;
  for (Technique t : all_techniques()) s += (s.empty() ? "" : ", ") + to_string(t);
  return s;
}

void TechniqueConfig::validate() const {
  buffer.validate();
  if (!has_early_cull(technique) && buffer.early_cull_tau > 0.0f)
    throw std::invalid_argument("early cull is the HA-buffer's and sorted lists': technique " + to_string(technique) +
                                " has none");
  if (occupancy && technique != Technique::KBuffer)
    throw std::invalid_argument("occupancy maps are the k-buffer's, not " + to_string(technique) + "'s");
  if (occupancy_words == 0 || occupancy_words > HABUFFER_MAX_OCCUPANCY_WORDS)
    throw std::invalid_argument("occupancy words " + std::to_string(occupancy_words) + " outside [1, " +
                                std::to_string(HABUFFER_MAX_OCCUPANCY_WORDS) + "]");
  if (!(depth_range.near_t >= 0.0f && depth_range.near_t < depth_range.far_t && depth_range.far_t <= 1.0f))
    throw std::invalid_argument("depth range [" + std::to_string(depth_range.near_t) + ", " +
                                std::to_string(depth_range.far_t) + "] is not an interval within [0, 1]");
  const std::uint64_t pixels = buffer.screen.area();
  if (uses_pool(technique)) {
    // Links are 32-bit node numbers with 0 for "none".
    if (pool_capacity == 0 || pool_capacity >= UINT32_MAX)
      throw std::invalid_argument("node pool of " + std::to_string(pool_capacity) +
                                  " nodes: must be in [1, 2^32 - 2] (0, automatic, is for build_technique and the GL "
                                  "containers, which size it)");
  }
  if (occupancy && std::uint64_t{occupancy_words} * pixels > UINT32_MAX)
    throw std::invalid_argument(std::to_string(occupancy_words) + " occupancy words of screen " + buffer.screen.str() +
                                " exceed 2^32 - 1 words");
  if (uses_layers(technique)) {
    if (layers == 0) throw std::invalid_argument(to_string(technique) + " needs at least 1 layer per pixel");
    if (std::uint64_t{layers} * pixels > UINT32_MAX)
      throw std::invalid_argument(std::to_string(layers) + " layers of screen " + buffer.screen.str() +
                                  " exceed 2^32 - 1 slots");
  }
}

std::string TechniqueConfig::limit() const {
  try {
    validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TechniqueConfig TechniqueConfig::grown(const ResizePolicy& policy, std::uint64_t nodes_requested,
                                       std::uint32_t most_arrived) const {
  TechniqueConfig c = *this;
  switch (technique) {
    case Technique::Ha: c.buffer.table = policy.grown(buffer.table_or_screen()); break;
    case Technique::Lists:
    case Technique::SortedLists: c.pool_capacity = policy.grown(pool_capacity, nodes_requested); break;
    case Technique::Arrays: c.layers = std::max(most_arrived, layers + 1); break;
    // The k-buffer does not know how deep its pixels were: it doubles K.
    case Technique::KBuffer: c.layers = layers * 2; break;
    case Technique::Wboit:
    case Technique::Blend: break;  // they drop nothing
  }
  return c;
}

TechniqueConfig ha_technique_config(const BufferConfig& buffer) {
  TechniqueConfig c;
  c.technique = Technique::Ha;
  c.buffer = buffer;
  return c;
}

TechniqueConfig validated_as(TechniqueConfig config, Technique t) {
  if (config.technique != t)
    throw std::invalid_argument("technique " + to_string(t) + "'s container refuses a configuration of technique " +
                                to_string(config.technique));
  config.validate();
  return config;
}

void occupancy_geometry(const TechniqueConfig& c, std::uint32_t& near_code, std::uint32_t& bucket_codes) {
  const RecordLayout layout = c.buffer.record_layout();
  near_code = layout.depth_code(c.depth_range.near_t);
  const std::uint32_t far_code = layout.depth_code(c.depth_range.far_t);
  const std::uint64_t span = std::uint64_t{near_code} - far_code + 1;
  const std::uint64_t buckets = std::uint64_t{32} * c.occupancy_words;
  bucket_codes = static_cast<std::uint32_t>((span + buckets - 1) / buckets);
}

}  // namespace habuffer
