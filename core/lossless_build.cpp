#include "habuffer/lossless_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_frames.h"

namespace habuffer {

OffsetSequence OffsetSource::make(Extent table, std::uint32_t count) const {
  if (generator == OffsetGenerator::List) return OffsetSequence::from_list(table, count, list);
  return OffsetSequence::make(generator, table, count, seed);
}

BuildResult build(const BufferConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                  const InsertOptions& options, const ResizePolicy& policy, std::uint32_t max_attempts) {
  return ha_build_result(build_technique(ha_technique_config(config), offsets, fragments, options, policy,
                                         max_attempts));
}

BuildResult ha_build_result(TechniqueBuild b) {
  if (!b.buffer || b.buffer->hash_table() != b.buffer.get())
    throw std::invalid_argument("a build of technique " +
                                (b.buffer ? to_string(b.buffer->technique()) : std::string("(none)")) +
                                " is not an HA-buffer's");
  return BuildResult{std::move(static_cast<HaBuffer&>(*b.buffer)), b.counters, std::move(b.attempts), b.too_deep};
}

std::unique_ptr<FragmentBuffer> make_fragment_buffer(const TechniqueConfig& config, const OffsetSource& offsets) {
  return descriptor(config.technique).make(config, offsets);
}

std::optional<PixelDepth> pixel_beyond_every_table(const TechniqueConfig& c, std::span<const Fragment> fragments) {
  if (!uses_table(c.technique) || c.buffer.early_cull_tau > 0.0f) return std::nullopt;
  const RecordLayout layout = c.buffer.record_layout();
  return pixel_deeper_than(fragments, c.buffer.screen, layout, layout.max_age());
}

TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy, std::uint32_t max_attempts) {
  TechniqueFrames frames(offsets, options, policy, max_attempts);
  frames.build(config, fragments);
  return frames.release();
}

}  // namespace habuffer
