#include "habuffer/techniques/kbuffer/kbuffer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/techniques/kbuffer/detail/kbuffer_kernel.h"
#include "habuffer/detail/technique_parallel.h"

namespace habuffer {
namespace {

// The occupancy map's fill step for one fragment (kbuffer.glsl's kb_fill_fragment).
template <class Kernel>
void fill(Kernel& k, const Fragment& f) {
  k.kb_fill_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage);
}

}  // namespace

KBuffer::KBuffer(const TechniqueConfig& config)
    : config_(validated_as(config, Technique::KBuffer)), params_(kernel_uniforms(config_)) {
  const std::uint64_t slots = std::uint64_t{config_.layers} * config_.buffer.screen.area();
  if (wide()) slots64_.assign(slots, 0);
  else slots32_.assign(slots, 0);
  if (config_.occupancy) {
    occupancy_.assign(std::uint64_t{config_.occupancy_words} * config_.buffer.screen.area(), 0);
    limits_.assign(config_.buffer.screen.area(), 0);
  }
}

template <class Word>
KBufferBuffers<Word> KBuffer::buffers() const {
  // The kernel's read-only uses (length, composite) never write through these.
  auto* self = const_cast<KBuffer*>(this);
  Word* slots = nullptr;
  if constexpr (sizeof(Word) == 8) slots = self->slots64_.data();
  else slots = self->slots32_.data();
  return {slots, self->occupancy_.data(), self->limits_.data()};
}

template <class Word>
Counters KBuffer::insert_words(std::span<const Fragment> fragments, const detail::InsertPlan& plan) {
  const auto make = [&](auto concurrent) { return KBufferKernel<Word, decltype(concurrent)::value>(params_, buffers<Word>()); };
  if (config_.occupancy && !plan.owned_rows) {
    // Fill pass, then count pass: the limits cover every fragment of the
    // frame so far (earlier batches' bits stay), so they only ever tighten.
    detail::for_insert_threads(fragments, screen(), plan, make,
                               [](auto& k, std::span<const Fragment> mine, std::uint32_t, auto) {
                                 for (const Fragment& f : mine) fill(k, f);
                               });
    detail::for_every_pixel(
        screen(), plan.threads, [&] { return KBufferKernel<Word, false>(params_, buffers<Word>()); },
        [](auto& k, glm::uvec2 p, std::uint32_t) { k.kb_count_pixel(p); });
  }
  std::vector<detail::SliceCounters> parts(plan.threads);
  const auto insert_mine = [&](auto& k, std::span<const Fragment> mine, std::uint32_t t, auto owns) {
    if (config_.occupancy && plan.owned_rows) {
      // The three passes on the thread's own pixels, which no other thread
      // touches: no barrier between them.
      for (const Fragment& f : mine)
        if (owns(f)) fill(k, f);
      owns.rows(screen(), [&](std::uint32_t y) {
        for (std::uint32_t x = 0; x < screen().x; ++x) k.kb_count_pixel(glm::uvec2(x, y));
      });
    }
    // A local tally: counters in memory could alias the buffers and force a store per fragment.
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
    for (const Fragment& f : mine)
      if (owns(f)) ++tally[k.kb_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba)];
    parts[t].c.add_tally(tally);
  };
  detail::for_insert_threads(fragments, screen(), plan, make, insert_mine);
  Counters total;
  for (const auto& part : parts) total += part.c;
  return total;
}

Counters KBuffer::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  const detail::InsertPlan plan = detail::insert_plan(
      options, Technique::KBuffer, detail::insert_work(Technique::KBuffer, fragments.size(), config_.occupancy, screen()));
  detail::check_on_screen(fragments, screen(), plan.threads);
  const auto alone = gate_.alone();  // the batch runs alone (insert_gate.h)
  return wide() ? insert_words<std::uint64_t>(fragments, plan) : insert_words<std::uint32_t>(fragments, plan);
}

std::uint64_t KBuffer::clear() {
  const auto alone = gate_.alone();
  const std::uint64_t held = count_stored();
  empty();
  return held;
}

void KBuffer::reset() {
  const auto alone = gate_.alone();
  empty();
}

void KBuffer::empty() {
  std::fill(slots64_.begin(), slots64_.end(), 0);
  std::fill(slots32_.begin(), slots32_.end(), 0u);
  std::fill(occupancy_.begin(), occupancy_.end(), 0u);
  std::fill(limits_.begin(), limits_.end(), 0u);
}

std::uint64_t KBuffer::record(std::uint64_t slot) const { return wide() ? slots64_[slot] : slots32_[slot]; }

std::uint64_t KBuffer::count_stored() const {
  std::uint64_t n = 0;
  for (std::uint64_t s = 0; s < capacity(); ++s) n += record(s) != 0 ? 1 : 0;
  return n;
}

std::uint32_t KBuffer::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  out.clear();
  const RecordLayout layout = config_.buffer.record_layout();
  const std::uint64_t pixel = x + std::uint64_t{y} * screen().x;
  std::uint32_t reads = 0;
  for (std::uint32_t k = 0; k < params_.habuffer_layers; ++k) {
    ++reads;
    const std::uint64_t r = record(std::uint64_t{k} * screen().area() + pixel);
    if (r == 0) break;
    out.push_back({0, layout.code(r), layout.data(r)});
  }
  return reads;
}

std::vector<glm::vec4> KBuffer::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  const auto composite = [](auto& k, glm::uvec2 p, glm::vec3 background) { return k.kb_composite(p, background); };
  if (wide())
    return detail::composite_image(
        screen(), backgrounds, threads, [&] { return KBufferKernel<std::uint64_t, false>(params_, buffers<std::uint64_t>()); },
        composite);
  return detail::composite_image(
      screen(), backgrounds, threads, [&] { return KBufferKernel<std::uint32_t, false>(params_, buffers<std::uint32_t>()); },
      composite);
}

std::uint64_t KBuffer::memory_bytes() const {
  return slots64_.size() * 8 + slots32_.size() * 4 + occupancy_.size() * 4 + limits_.size() * 4;
}

void KBuffer::import_state(std::span<const std::uint32_t> slot_words, std::span<const std::uint32_t> limits) {
  const auto alone = gate_.alone();
  const std::uint64_t words = wide() ? slots64_.size() * 2 : slots32_.size();
  if (slot_words.size() != words || limits.size() != limits_.size())
    throw std::invalid_argument("imported k-buffer has " + std::to_string(slot_words.size()) + " words and " +
                                std::to_string(limits.size()) + " limits, the buffer " + std::to_string(words) +
                                " and " + std::to_string(limits_.size()));
  // Each pixel's layers: records of age 1 (0 is an empty slot), nearest
  // first, empty slots only after the last record.
  const RecordLayout layout = config_.buffer.record_layout();
  const std::uint64_t pixels = screen().area();
  const auto word = [&](std::uint64_t s) {
    return wide() ? slot_words[2 * s] | (std::uint64_t{slot_words[2 * s + 1]} << 32) : std::uint64_t{slot_words[s]};
  };
  std::vector<glm::uvec2> list;
  for (std::uint64_t p = 0; p < pixels; ++p) {
    list.clear();
    bool ended = false;
    for (std::uint32_t k = 0; k < params_.habuffer_layers; ++k) {
      const std::uint64_t r = word(k * pixels + p);
      const std::string where = "imported k-buffer: layer " + std::to_string(k) + " of pixel (" +
                                std::to_string(p % screen().x) + "," + std::to_string(p / screen().x) + ")";
      if (r == 0) {
        ended = true;
        continue;
      }
      if (ended) throw std::invalid_argument(where + " holds a record after an empty layer");
      if (layout.age(r) != 1)
        throw std::invalid_argument(where + " holds a record of age " + std::to_string(layout.age(r)) + ", not 1");
      list.emplace_back(layout.code(r), layout.data(r));
    }
    // The k-buffer keeps a pixel's layers in record order (kbuffer.glsl
    // compares whole records), so an entry lies before another when its
    // record of age 1 is the greater.
    detail::check_imported_list(list, layout, p, screen(), "imported k-buffer", [&](glm::uvec2 a, glm::uvec2 b) {
      return layout.pack(1, a.x, a.y) > layout.pack(1, b.x, b.y);
    });
  }
  const std::uint32_t buckets = 32 * config_.occupancy_words;
  if (std::any_of(limits.begin(), limits.end(), [&](std::uint32_t b) { return b > buckets; }))
    throw std::invalid_argument("imported k-buffer: an occupancy limit above " +
                                std::to_string(buckets) + " buckets");
  if (wide())
    for (std::size_t s = 0; s < slots64_.size(); ++s)
      slots64_[s] = slot_words[2 * s] | (std::uint64_t{slot_words[2 * s + 1]} << 32);
  else
    std::copy(slot_words.begin(), slot_words.end(), slots32_.begin());
  std::copy(limits.begin(), limits.end(), limits_.begin());
}

std::uint32_t KBuffer::occupancy_limit(std::uint32_t x, std::uint32_t y) const {
  check_pixel(x, y, screen());
  if (!config_.occupancy) throw std::logic_error("the k-buffer's occupancy map is off");
  return limits_[x + std::size_t{y} * screen().x];
}

}  // namespace habuffer
