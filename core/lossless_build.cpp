#include "habuffer/lossless_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/fixed_arrays.h"
#include "habuffer/linked_lists.h"
#include "habuffer/kbuffer.h"
#include "habuffer/blended_image.h"

namespace habuffer {

OffsetSequence OffsetSource::make(Extent table, std::uint32_t count) const {
  if (generator == OffsetGenerator::List) return OffsetSequence::from_list(table, count, list);
  return OffsetSequence::make(generator, table, count, seed);
}

BuildResult build(const BufferConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                  const InsertOptions& options, const ResizePolicy& policy, std::uint32_t max_attempts) {
  TechniqueBuild b = build_technique(ha_technique_config(config), offsets, fragments, options, policy,
                                     max_attempts);
  return BuildResult{std::move(static_cast<HaBuffer&>(*b.buffer)), b.counters, std::move(b.attempts), b.too_deep};
}

std::unique_ptr<FragmentBuffer> make_fragment_buffer(const TechniqueConfig& config, const OffsetSource& offsets) {
  switch (config.technique) {
    case Technique::Ha: {
      config.validate();  // before the offsets are made for its table
      const Extent table = config.buffer.table_or_screen();
      return std::make_unique<HaBuffer>(config.buffer, offsets.make(table, config.buffer.record_layout().max_age()));
    }
    case Technique::Lists:
    case Technique::SortedLists: return std::make_unique<LinkedLists>(config);
    case Technique::Arrays: return std::make_unique<FixedArrays>(config);
    case Technique::KBuffer: return std::make_unique<KBuffer>(config);
    case Technique::Wboit:
    case Technique::Blend: return std::make_unique<BlendedImage>(config);
  }
  throw std::invalid_argument("unknown technique");
}

namespace {

// The lossless attempt after `buffer` dropped fragments.
TechniqueConfig next_attempt(const TechniqueConfig& c, const FragmentBuffer& buffer, const ResizePolicy& policy) {
  const auto* lists = dynamic_cast<const LinkedLists*>(&buffer);
  const auto* arrays = dynamic_cast<const FixedArrays*>(&buffer);
  return c.grown(policy, lists != nullptr ? lists->requested() : 0, arrays != nullptr ? arrays->largest_overflow() : 0);
}

}  // namespace

std::optional<PixelDepth> pixel_beyond_every_table(const TechniqueConfig& c, std::span<const Fragment> fragments) {
  if (c.technique != Technique::Ha || c.buffer.early_cull_tau > 0.0f) return std::nullopt;
  const RecordLayout layout = c.buffer.record_layout();
  return pixel_deeper_than(fragments, c.buffer.screen, layout, layout.max_age());
}

TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy, std::uint32_t max_attempts) {
  if (max_attempts == 0) throw std::invalid_argument("at least one build attempt is needed");
  policy.validate();
  TechniqueConfig c = config;
  c.buffer.table = config.buffer.table_or_screen();
  // The automatic pool (0), as render's --pool auto: the fragments at
  // grow_at use, so one pool holds them all.
  if (uses_pool(c.technique) && c.pool_capacity == 0)
    c.pool_capacity = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(fragments.size()) / policy.grow_at)));
  std::vector<BuildAttempt> attempts;
  for (;;) {
    std::unique_ptr<FragmentBuffer> buffer = make_fragment_buffer(c, offsets);
    const Counters counters = buffer->insert(fragments, options);
    attempts.push_back({c.technique == Technique::Ha ? c.buffer.table : Extent{}, counters, buffer->capacity()});
    if (counters.failures() == 0 || attempts.size() >= max_attempts)
      return {std::move(buffer), counters, std::move(attempts), false, std::nullopt};
    if (std::optional<PixelDepth> deep = counters.failed_age > 0 ? pixel_beyond_every_table(c, fragments) : std::nullopt)
      return {std::move(buffer), counters, std::move(attempts), false, deep};
    const TechniqueConfig next = next_attempt(c, *buffer, policy);
    if (!next.limit().empty())  // no larger buffer can be built: the last attempt's result, marked
      return {std::move(buffer), counters, std::move(attempts), true, std::nullopt};
    c = next;
  }
}

}  // namespace habuffer
