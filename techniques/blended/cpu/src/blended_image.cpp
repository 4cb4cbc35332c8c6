#include "habuffer/techniques/blended/blended_image.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/techniques/blended/detail/blended_kernel.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer {
TechniqueConfig BlendedImage::checked_config(const TechniqueConfig& c) {
  if (stores_lists(c.technique))
    throw std::invalid_argument("a blended image is wboit or blend, not " + to_string(c.technique));
  return validated_as(c, c.technique);
}

BlendedImage::BlendedImage(const TechniqueConfig& config)
    : config_(checked_config(config)), params_(kernel_uniforms(config_)) {
  clear();
}

Counters BlendedImage::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  detail::InsertPlan plan =
      detail::insert_plan(options, technique(), detail::insert_work(technique(), fragments.size(), false, screen()));
  detail::check_on_screen(fragments, screen(), plan.threads);
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  // Threads own rows of pixels whatever the mode: blending has no atomic
  // version, and each pixel then blends its fragments in stream order, as one
  // thread does, bit for bit.
  plan.owned_rows = plan.threads > 1;
  std::vector<detail::SliceCounters> parts(plan.threads);
  const std::uint32_t width = screen().x;
  detail::for_insert_threads(
      fragments, screen(), plan, [&](auto) { return BlendedKernel(params_); },
      [&](BlendedKernel& k, std::span<const Fragment> mine, std::uint32_t t, auto owns) {
        std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
        for (const Fragment& f : mine) {
          if (!owns(f)) continue;
          if (!k.ha_depth_valid(f.depth)) {
            ++tally[HABUFFER_INVALID];
            continue;
          }
          ++tally[HABUFFER_BLENDED];
          const std::size_t p = f.x + std::size_t{f.y} * width;
          const glm::vec4 c = k.ha_unpack_rgba(f.rgba);
          if (weighted()) {
            accum_[p] += k.wb_accum_term(f.depth, c);
            revealage_[p] *= 1.0f - c.a;
          } else {
            accum_[p] = k.bl_over(accum_[p], c);
          }
        }
        parts[t].c.add_tally(tally);
      });
  Counters total;
  for (const auto& part : parts) total += part.c;
  return total;
}

std::uint64_t BlendedImage::clear() {
  const auto alone = gate_.alone();
  accum_.assign(screen().area(), weighted() ? glm::vec4(0.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  revealage_.assign(weighted() ? screen().area() : 0, 1.0f);
  return 0;
}

std::uint32_t BlendedImage::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  out.clear();
  return 0;
}

std::vector<glm::vec4> BlendedImage::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  const std::uint32_t width = screen().x;
  return detail::composite_image(
      screen(), backgrounds, threads, [&] { return BlendedKernel(params_); },
      [&](BlendedKernel& k, glm::uvec2 p, glm::vec3 background) {
        const std::size_t i = p.x + std::size_t{p.y} * width;
        return weighted() ? k.wb_finish(accum_[i], revealage_[i], background) : k.bl_finish(accum_[i], background);
      });
}

std::uint64_t BlendedImage::memory_bytes() const { return accum_.size() * sizeof(glm::vec4) + revealage_.size() * 4; }

void BlendedImage::import_state(std::span<const glm::vec4> accum, std::span<const float> revealage) {
  const auto alone = gate_.alone();
  if (accum.size() != accum_.size() || revealage.size() != revealage_.size())
    throw std::invalid_argument("imported accumulators have " + std::to_string(accum.size()) + " pixels and " +
                                std::to_string(revealage.size()) + " revealages, the image " +
                                std::to_string(accum_.size()) + " and " + std::to_string(revealage_.size()));
  std::copy(accum.begin(), accum.end(), accum_.begin());
  std::copy(revealage.begin(), revealage.end(), revealage_.begin());
}

}  // namespace habuffer
