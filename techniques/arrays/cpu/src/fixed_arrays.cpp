#include "habuffer/techniques/arrays/fixed_arrays.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/detail/technique_parallel.h"

namespace habuffer {
FixedArrays::FixedArrays(const TechniqueConfig& config)
    : config_(validated_as(config, Technique::Arrays)),
      params_(kernel_uniforms(config_)),
      counts_(config_.buffer.screen.area(), 0),
      layers_(std::uint64_t{config_.layers} * config_.buffer.screen.area()) {}

ArraysBuffers FixedArrays::buffers() const {
  // The kernel's read-only uses (composite) never write through these.
  auto* self = const_cast<FixedArrays*>(this);
  return {self->counts_.data(), self->layers_.data(), &self->max_arrived_};
}

Counters FixedArrays::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  const detail::InsertPlan plan = detail::insert_plan(
      options, Technique::Arrays, detail::insert_work(Technique::Arrays, fragments.size(), true, screen()));
  detail::check_on_screen(fragments, screen(), plan.threads);
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  if (fragments.size() > UINT32_MAX - std::uint64_t{*std::max_element(counts_.begin(), counts_.end())})
    throw std::invalid_argument("fixed arrays count a pixel's fragments in 32 bits: " +
                                std::to_string(fragments.size()) + " fragments in one batch are too many");
  const auto make = [&](auto concurrent) { return ArraysKernel<decltype(concurrent)::value>(params_, buffers()); };
  const auto make_sorter = [&] { return ArraysKernel<false>(params_, buffers()); };
  return detail::insert_then_sort(
      fragments, screen(), plan, make, make_sorter,
      [](auto& k, const Fragment& f) { return k.fa_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba); },
      [](auto& k, glm::uvec2 p) { return k.fa_sort_pixel(p); });
}

std::uint64_t FixedArrays::clear() {
  const auto alone = gate_.alone();
  const std::uint64_t held = count_stored();
  empty();
  return held;
}

void FixedArrays::reset() {
  const auto alone = gate_.alone();
  empty();
}

void FixedArrays::empty() {
  std::fill(counts_.begin(), counts_.end(), 0u);
  max_arrived_ = 0;
}

std::uint64_t FixedArrays::count_stored() const {
  std::uint64_t n = 0;
  for (std::uint32_t c : counts_) n += c;
  return n;
}

std::uint32_t FixedArrays::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  out.clear();
  const std::size_t pixel = x + std::size_t{y} * screen().x;
  for (std::uint32_t k = 0; k < counts_[pixel]; ++k) {
    const glm::uvec2 e = layers_[k * screen().area() + pixel];
    out.push_back({0, e.x, e.y});
  }
  return 1 + counts_[pixel];
}

std::vector<glm::vec4> FixedArrays::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  return detail::composite_image(
      screen(), backgrounds, threads, [&] { return ArraysKernel<false>(params_, buffers()); },
      [](auto& k, glm::uvec2 p, glm::vec3 background) { return k.fa_composite(p, background); });
}

std::uint64_t FixedArrays::memory_bytes() const {
  return counts_.size() * 4 + layers_.size() * sizeof(glm::uvec2) + sizeof max_arrived_;
}

void FixedArrays::import_state(std::span<const std::uint32_t> counts, std::span<const glm::uvec2> layers,
                               std::uint32_t largest_overflow) {
  const auto alone = gate_.alone();
  if (counts.size() != counts_.size() || layers.size() != layers_.size())
    throw std::invalid_argument("imported arrays have " + std::to_string(counts.size()) + " pixels and " +
                                std::to_string(layers.size()) + " layers, the buffer " + std::to_string(counts_.size()) +
                                " and " + std::to_string(layers_.size()));
  if (std::any_of(counts.begin(), counts.end(), [&](std::uint32_t n) { return n > params_.habuffer_layers; }))
    throw std::invalid_argument("imported arrays hold more than " + std::to_string(params_.habuffer_layers) + " layers in a pixel");
  const RecordLayout layout = config_.buffer.record_layout();
  ArraysKernel<false> order(params_, buffers());  // the arrays' entry order (ha_entries.glsl)
  const auto before = [&](glm::uvec2 a, glm::uvec2 b) { return order.ha_entry_before(a, b); };
  std::vector<glm::uvec2> list;
  for (std::size_t p = 0; p < counts.size(); ++p) {
    list.clear();
    for (std::uint32_t k = 0; k < counts[p]; ++k) list.push_back(layers[k * counts.size() + p]);
    detail::check_imported_list(list, layout, p, screen(), "imported arrays", before);
  }
  std::copy(counts.begin(), counts.end(), counts_.begin());
  std::copy(layers.begin(), layers.end(), layers_.begin());
  max_arrived_ = largest_overflow;
}

}  // namespace habuffer
