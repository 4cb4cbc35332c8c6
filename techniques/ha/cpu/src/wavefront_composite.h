// The HA-buffer's composite as a wavefront on the CPU (issue 36).
//
// SPEC 7 composites a pixel by walking its ages 1..M[cell], and the shared
// ha_composite (shared/ha_traverse.glsl) does exactly that, one pixel at a
// time. On the CPU every age of a deep pixel is a dependent miss in a table
// larger than the caches. Coherent probing puts neighbouring pixels' probes
// of one age in neighbouring slots, so a row of kWavefrontPixels pixels
// stepped together, age by age, reads one or two cache lines per age, and
// the next age's lines can be prefetched while this age blends: the GPU's
// warp, arranged by hand. Each pixel meets its records in the same order and
// blends them with the same shared operations (ha_visit, ha_blend_under,
// ha_finish), so the image is ha_composite's bit for bit
// (tests/test_compositing.cpp).
#pragma once

#include <algorithm>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace habuffer::detail {

// Pixels a wavefront steps together: 8 records of 8 bytes, one cache line.
inline constexpr std::uint32_t kWavefrontPixels = 8;

// Row y's pixels [0, width) composited into out[0, width) over
// background(x), kWavefrontPixels at a time (see above).
template <class Kernel, class Background>
void composite_row_wavefront(Kernel& k, std::uint32_t y, std::uint32_t width, Background background,
                             glm::vec4* out) {
  for (std::uint32_t x0 = 0; x0 < width; x0 += kWavefrontPixels) {
    const std::uint32_t n = std::min(kWavefrontPixels, width - x0);
    std::uint32_t amax[kWavefrontPixels];
    glm::vec4 c[kWavefrontPixels];
    std::uint32_t active = 0, deepest = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      amax[i] = k.ha_load_max_age(k.ha_cell(glm::uvec2(x0 + i, y)));
      c[i] = glm::vec4(0.0f);
      if (amax[i] != 0) active |= 1u << i;
      deepest = std::max(deepest, amax[i]);
    }
    glm::uvec2 h = k.ha_probe(glm::uvec2(x0, y), 1);  // the first pixel's probe at age a
    for (std::uint32_t a = 1; active != 0 && a <= deepest; ++a) {
      // Neighbouring pixels probe neighbouring slots of one row unless the
      // row of the table wraps between them (coherent probing, SPEC 3).
      const bool contiguous = h.x + n <= k.ha_table_size.x;
      const auto first = k.ha_slot(h);
      if (a < deepest) {  // the next age's lines, while this age blends
        h = k.ha_probe(glm::uvec2(x0, y), a + 1);
        __builtin_prefetch(k.slots() + k.ha_slot(h));
        if (h.x + n <= k.ha_table_size.x) __builtin_prefetch(k.slots() + k.ha_slot(h) + (n - 1));
      }
      for (std::uint32_t left = active; left != 0; left &= left - 1) {
        const auto i = static_cast<std::uint32_t>(__builtin_ctz(left));
        if (a > amax[i]) {
          active &= ~(1u << i);
          continue;
        }
        const auto r = k.ha_load_slot(contiguous ? first + i : k.ha_slot(k.ha_probe(glm::uvec2(x0 + i, y), a)));
        const std::uint32_t v = k.ha_visit(r, a);
        if (v == HABUFFER_VISIT_STOP)
          active &= ~(1u << i);
        else if (v == HABUFFER_VISIT_EMIT)
          c[i] = k.ha_blend_under(c[i], k.ha_unpack_rgba(k.ha_data(r)));
      }
    }
    for (std::uint32_t i = 0; i < n; ++i) out[x0 + i] = k.ha_finish(c[i], background(x0 + i));
  }
}

}  // namespace habuffer::detail
