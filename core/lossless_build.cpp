#include "habuffer/lossless_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/fixed_arrays.h"
#include "habuffer/linked_lists.h"

namespace habuffer {

OffsetSequence OffsetSource::make(Extent table, std::uint32_t count) const {
  if (generator == OffsetGenerator::List) return OffsetSequence::from_list(table, count, list);
  return OffsetSequence::make(generator, table, count, seed);
}

BuildResult build(const BufferConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                  const InsertOptions& options, const ResizePolicy& policy, std::uint32_t max_attempts) {
  if (max_attempts == 0) throw std::invalid_argument("at least one build attempt is needed");
  policy.validate();
  BufferConfig c = config;
  c.table = config.table_or_screen();
  const std::uint32_t amax = c.record_layout().max_age();
  std::vector<BuildAttempt> attempts;
  for (;;) {
    HaBuffer buffer(c, offsets.make(c.table, amax));
    const Counters counters = buffer.insert(fragments, options);
    attempts.push_back({c.table, counters, c.table.area()});
    if (counters.failures() == 0 || attempts.size() >= max_attempts)
      return BuildResult{std::move(buffer), counters, std::move(attempts)};
    c.table = policy.grown(c.table);
  }
}

std::unique_ptr<FragmentBuffer> make_fragment_buffer(const TechniqueConfig& config, const OffsetSource& offsets) {
  switch (config.technique) {
    case Technique::Ha: {
      const Extent table = config.buffer.table_or_screen();
      return std::make_unique<HaBuffer>(config.buffer, offsets.make(table, config.buffer.record_layout().max_age()));
    }
    case Technique::Lists: return std::make_unique<LinkedLists>(config);
    case Technique::Arrays: return std::make_unique<FixedArrays>(config);
  }
  throw std::invalid_argument("unknown technique");
}

namespace {

// The configuration of the next lossless attempt after `buffer` dropped fragments.
TechniqueConfig grown(TechniqueConfig c, const FragmentBuffer& buffer, const ResizePolicy& policy) {
  switch (c.technique) {
    case Technique::Ha: c.buffer.table = policy.grown(c.buffer.table_or_screen()); break;
    case Technique::Lists: {
      const auto stepped = static_cast<std::uint64_t>(std::ceil(static_cast<double>(c.pool_capacity) * (1.0 + policy.step)));
      c.pool_capacity = std::max(static_cast<const LinkedLists&>(buffer).requested(), stepped);
      break;
    }
    case Technique::Arrays:
      c.layers = std::max(static_cast<const FixedArrays&>(buffer).largest_overflow(), c.layers + 1);
      break;
  }
  return c;
}

}  // namespace

TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy, std::uint32_t max_attempts) {
  if (max_attempts == 0) throw std::invalid_argument("at least one build attempt is needed");
  policy.validate();
  if (config.technique == Technique::Ha) {
    BuildResult b = build(config.buffer, offsets, fragments, options, policy, max_attempts);
    return {std::make_unique<HaBuffer>(std::move(b.buffer)), b.counters, std::move(b.attempts)};
  }
  TechniqueConfig c = config;
  std::vector<BuildAttempt> attempts;
  for (;;) {
    std::unique_ptr<FragmentBuffer> buffer = make_fragment_buffer(c, offsets);
    const Counters counters = buffer->insert(fragments, options);
    attempts.push_back({Extent{}, counters, buffer->capacity()});
    if (counters.failures() == 0 || attempts.size() >= max_attempts)
      return {std::move(buffer), counters, std::move(attempts)};
    c = grown(c, *buffer, policy);
  }
}

}  // namespace habuffer
