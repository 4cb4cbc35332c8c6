#include "habuffer/lossless_build.h"

#include <stdexcept>

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

}  // namespace habuffer
