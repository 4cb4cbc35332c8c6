#include "habuffer/lossless_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_frames.h"

namespace habuffer {

BuildResult build(const BufferConfig& config, const OffsetSource& offsets, std::span<const Fragment> fragments,
                  const InsertOptions& options, const ResizePolicy& policy, std::uint32_t max_attempts) {
  return ha_build_result(build_technique(ha_technique_config(config), offsets, fragments, options, policy,
                                         max_attempts));
}

BuildResult ha_build_result(TechniqueBuild b) {
  if (!b.buffer || as_hash_table(*b.buffer) == nullptr)
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

AttemptLimit lossless_attempts(const TechniqueConfig& config, std::span<const Fragment> fragments,
                               std::uint32_t max_attempts) {
  if (max_attempts <= 1) return {max_attempts, std::nullopt};
  AttemptLimit limit{max_attempts, pixel_beyond_every_table(config, fragments)};
  if (limit.too_deep) limit.attempts = 1;
  return limit;
}

std::optional<PixelLoss> pixel_most_lost(const FragmentBuffer& buffer, std::span<const Fragment> fragments) {
  const TechniqueConfig c = buffer.technique_config();
  if (!stores_lists(c.technique) || c.buffer.early_cull_tau > 0.0f) return std::nullopt;
  const Extent screen = buffer.screen();
  const RecordLayout layout = c.buffer.record_layout();
  const auto valid = [&](const Fragment& f) {
    return f.x < screen.x && f.y < screen.y && layout.fragment_valid(f.depth, f.coverage);
  };
  std::vector<std::uint32_t> count(screen.area(), 0);  // valid fragments per pixel, row-major
  for (const Fragment& f : fragments)
    if (valid(f)) {
      std::uint32_t& n = count[f.x + std::size_t{f.y} * screen.x];
      n += n < UINT32_MAX ? 1 : 0;
    }
  // Only pixels with more fragments than their list holds can have lost a record.
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::vector<std::uint32_t> held(screen.area(), kNone);
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < screen.y; ++y)
    for (std::uint32_t x = 0; x < screen.x; ++x) {
      const std::size_t i = x + std::size_t{y} * screen.x;
      if (count[i] == 0) continue;
      buffer.list(x, y, list);
      if (count[i] > list.size()) held[i] = static_cast<std::uint32_t>(list.size());
    }
  std::vector<std::pair<std::uint64_t, std::uint64_t>> records;  // (pixel, record) of those pixels
  for (const Fragment& f : fragments) {
    if (!valid(f)) continue;
    const std::uint64_t i = f.x + std::uint64_t{f.y} * screen.x;
    if (held[i] == kNone) continue;
    records.emplace_back(i, std::uint64_t{layout.fragment_code(f.depth, f.coverage)} << 32 | (layout.has_data() ? f.rgba : 0u));
  }
  std::sort(records.begin(), records.end());
  records.erase(std::unique(records.begin(), records.end()), records.end());
  std::optional<PixelLoss> most;
  for (std::size_t b = 0, e = 0; b < records.size(); b = e) {
    const std::uint64_t i = records[b].first;
    e = b;
    while (e < records.size() && records[e].first == i) ++e;
    const std::uint64_t distinct = e - b;
    const std::uint64_t lost = distinct > held[i] ? distinct - held[i] : 0;
    if (lost > 0 && (!most || lost > most->lost))
      most = PixelLoss{{static_cast<std::uint32_t>(i % screen.x), static_cast<std::uint32_t>(i / screen.x)}, distinct,
                       lost};
  }
  return most;
}

namespace {

std::string attempts_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " attempt" : " attempts"); }

std::string amax_text(std::uint32_t age_bits) {
  return "AMAX = 2^" + std::to_string(age_bits) + " - 1 = " + std::to_string((1u << age_bits) - 1);
}

}  // namespace

std::string lossless_failure_reason(const TechniqueBuild& result, std::span<const Fragment> fragments,
                                    std::uint32_t max_attempts, OptionSpelling spelling) {
  if (result.lossless() || !result.buffer) return {};
  const TechniqueConfig c = result.buffer->technique_config();
  const std::string made = " after " + attempts_text(result.attempts.size());
  const std::string allowed = option_value("max-attempts", std::to_string(max_attempts), spelling);
  // Growing cannot help (lossless_attempts' rule); one attempt asked no rule, so look now.
  std::optional<PixelDepth> too_deep = result.too_deep;
  if (!too_deep) too_deep = pixel_beyond_every_table(c, fragments);
  if (too_deep)
    return made + ": " + too_deep_message(*too_deep, c.buffer.age_bits, spelling) + "; more attempts cannot help (" +
           allowed + ")";
  std::string r = made + " (last " + result.buffer->capacity_text();
  if (uses_table(c.technique)) r += "; " + amax_text(c.buffer.age_bits);
  r += ")";
  if (const std::optional<PixelLoss> p = pixel_most_lost(*result.buffer, fragments))
    r += ": pixel (" + std::to_string(p->pixel.x) + ", " + std::to_string(p->pixel.y) + ") lost the most, " +
         std::to_string(p->lost) + " of its " + std::to_string(p->records) + " distinct records";
  if (result.growth_limited)
    return r + ": the next size cannot be built, so more attempts cannot help (" + allowed + ")";
  return r + ": raise " + option_name("max-attempts", spelling) + " above " + std::to_string(max_attempts);
}

void require_lossless(const TechniqueBuild& result, std::span<const Fragment> fragments, std::uint32_t max_attempts,
                      OptionSpelling spelling) {
  if (result.lossless()) return;
  throw DataError("lossless mode: " + loss_summary(result.counters) +
                  lossless_failure_reason(result, fragments, max_attempts, spelling));
}

TechniqueBuild build_technique(const TechniqueConfig& config, const OffsetSource& offsets,
                               std::span<const Fragment> fragments, const InsertOptions& options,
                               const ResizePolicy& policy, std::uint32_t max_attempts) {
  TechniqueFrames frames(offsets, options, policy, max_attempts);
  frames.build(config, fragments);
  return frames.release();
}

}  // namespace habuffer
