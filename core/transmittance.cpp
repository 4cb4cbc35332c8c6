#include "habuffer/transmittance.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/technique_descriptor.h"

namespace habuffer {

float list_transmittance(std::span<const ListEntry> nearest_first, std::uint32_t code, std::uint32_t bias) {
  // In 64 bits: code + bias never wraps (the GLSL clamps it to the largest code instead, the same test).
  const std::uint64_t front = std::uint64_t{code} + bias;
  float t = 1.0f;
  for (const ListEntry& e : nearest_first) {
    if (e.code <= front) break;
    // ha_alpha and the product as shared/ha_traverse.glsl writes them, so the paths agree bit for bit.
    const float alpha = static_cast<float>(e.data & 255u) * (1.0f / 255.0f);
    t *= 1.0f - alpha;
  }
  return t;
}

float transmittance(const FragmentBuffer& light, std::uint32_t x, std::uint32_t y, std::uint32_t code,
                    std::uint32_t bias) {
  const TechniqueConfig c = light.technique_config();
  const TechniqueDescriptor& d = descriptor(c.technique);
  if (!d.stores_lists)
    throw std::invalid_argument("technique " + std::string(d.name) + " stores no lists: it cannot serve as a light buffer");
  if (c.buffer.layout != Layout::L64)
    throw std::invalid_argument("a light buffer of L32 records carries no opacity: build it with L64 records");
  thread_local std::vector<ListEntry> entries;
  light.list(x, y, entries);
  return list_transmittance(entries, code, bias);
}

}  // namespace habuffer
