// FragmentBuffer::composite_image: one sample per pixel through the
// technique's own walk, or the per-pixel resolve of a multisampled buffer
// over each pixel's list (the shared ha_samples_* of ha_blend.glsl).
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/glsl_env.h"
#include "habuffer/shared/ha_constants.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer {
namespace {

// The shared blending and sample resolve, compiled as C++ (reads no buffer).
struct SampleBlender {
  HABUFFER_GLSL_CLASS_PRELUDE
#include "habuffer/shared/ha_blend.glsl"
};

}  // namespace

glm::vec4 resolve_samples(std::span<const ListEntry> records, const RecordLayout& layout, glm::vec3 background) {
  SampleBlender blend;
  SampleBlender::HaSampleColours c = blend.ha_samples_begin();
  const std::uint32_t mask = layout.coverage_mask();
  for (const ListEntry& e : records) blend.ha_samples_under(c, layout.samples(), e.code & mask, e.code & ~mask, e.data);
  return blend.ha_samples_finish(c, layout.samples(), background);
}

std::vector<glm::vec4> FragmentBuffer::composite_image(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads) const {
  const RecordLayout layout = technique_config().buffer.record_layout();
  if (layout.samples() <= 1 || !stores_lists(technique())) return composite_pixels(backgrounds, threads);
  const Extent s = screen();
  detail::check_backgrounds(s, backgrounds);
  std::vector<glm::vec4> image(s.area());
  detail::for_every_pixel(s, resolve_threads(threads, s.area()), [] { return std::vector<ListEntry>{}; },
                          [&](std::vector<ListEntry>& records, glm::uvec2 p, std::uint32_t) {
                            list(p.x, p.y, records);
                            const std::size_t i = p.x + std::size_t{p.y} * s.x;
                            image[i] = resolve_samples(records, layout, backgrounds[i]);
                          });
  return image;
}

}  // namespace habuffer
