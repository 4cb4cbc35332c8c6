#include "habuffer/technique.h"

#include <algorithm>
#include <stdexcept>

namespace habuffer {

std::string to_string(Technique t) {
  switch (t) {
    case Technique::Ha: return "ha";
    case Technique::Lists: return "lists";
    case Technique::Arrays: return "arrays";
  }
  return "?";
}

std::optional<Technique> parse_technique(std::string_view name) {
  for (Technique t : all_techniques())
    if (name == to_string(t)) return t;
  return std::nullopt;
}

std::vector<Technique> all_techniques() { return {Technique::Ha, Technique::Lists, Technique::Arrays}; }

std::string technique_names() {
  std::string s;
  for (Technique t : all_techniques()) s += (s.empty() ? "" : ", ") + to_string(t);
  return s;
}

void TechniqueConfig::validate() const {
  buffer.validate();
  if (technique != Technique::Ha && buffer.early_cull_tau > 0.0f)
    throw std::invalid_argument("early cull is the HA-buffer's: technique " + to_string(technique) + " has none");
  const std::uint64_t pixels = buffer.screen.area();
  if (technique == Technique::Lists) {
    // Links are 32-bit node numbers with 0 for "none".
    if (pool_capacity == 0 || pool_capacity >= UINT32_MAX)
      throw std::invalid_argument("node pool of " + std::to_string(pool_capacity) + " nodes: must be in [1, 2^32 - 2]");
  }
  if (technique == Technique::Arrays) {
    if (layers == 0) throw std::invalid_argument("fixed arrays need at least 1 layer per pixel");
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
    case Technique::Lists: c.pool_capacity = policy.grown(pool_capacity, nodes_requested); break;
    case Technique::Arrays: c.layers = std::max(most_arrived, layers + 1); break;
  }
  return c;
}

TechniqueConfig validated_as(TechniqueConfig config, Technique t) {
  config.technique = t;
  config.validate();
  return config;
}

}  // namespace habuffer
