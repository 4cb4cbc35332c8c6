#include "habuffer/transmittance.h"

#include <algorithm>

#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/glsl_env.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer {

namespace {

// shared/ha_shadow.glsl compiled as C++: the step the HA-buffer's walk takes.
struct ShadowStep {
  HABUFFER_GLSL_CLASS_PRELUDE
  using vec2 = glm::vec2;
#include "habuffer/shared/ha_shadow.glsl"
#include "habuffer/shared/ha_shadow_pcf.glsl"
};

}  // namespace

float list_transmittance(std::span<const ListEntry> nearest_first, std::uint32_t code, std::uint32_t bias) {
  // Capped at the largest 32-bit code: no record's code exceeds it, so the
  // test is the HA-buffer's, whose cap is its layout's largest code.
  ShadowStep step;
  const std::uint32_t front = step.ha_shadow_front(code, bias, UINT32_MAX);
  float t = 1.0f;
  for (const ListEntry& e : nearest_first) {
    if (e.code <= front) break;
    t = step.ha_shadow_through(t, e.data);
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

float transmittance_pcf(const FragmentBuffer& light, float wx, float wy, std::uint32_t code, std::uint32_t bias) {
  ShadowStep step;
  glm::uvec2 lo{0u}, hi{0u};
  glm::vec2 f{0.0f};
  step.ha_pcf_taps({wx, wy}, {light.screen().x, light.screen().y}, lo, hi, f);
  return step.ha_pcf_blend(transmittance(light, lo.x, lo.y, code, bias), transmittance(light, hi.x, lo.y, code, bias),
                           transmittance(light, lo.x, hi.y, code, bias), transmittance(light, hi.x, hi.y, code, bias), f);
}

}  // namespace habuffer
