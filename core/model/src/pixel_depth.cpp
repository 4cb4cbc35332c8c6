#include "habuffer/pixel_depth.h"

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "habuffer/shared/ha_constants.h"

namespace habuffer {

std::optional<PixelDepth> pixel_deeper_than(std::span<const Fragment> fragments, Extent screen,
                                            const RecordLayout& layout, std::uint64_t limit) {
  const auto on_screen = [&](const Fragment& f) {
    return f.x < screen.x && f.y < screen.y && layout.fragment_valid(f.depth, f.coverage);
  };
  std::vector<std::uint32_t> count(screen.area(), 0);
  for (const Fragment& f : fragments)
    if (on_screen(f)) {
      std::uint32_t& c = count[f.x + std::size_t{f.y} * screen.x];
      c += c < UINT32_MAX ? 1 : 0;
    }
  // Only pixels with more fragments than `limit` can have more records.
  std::unordered_map<std::uint64_t, std::vector<std::uint64_t>> deep;
  for (const Fragment& f : fragments) {
    if (!on_screen(f)) continue;
    const std::uint64_t index = f.x + std::uint64_t{f.y} * screen.x;
    if (count[index] <= limit) continue;
    const std::uint32_t data = layout.has_data() ? f.rgba : 0;
    deep[index].push_back(std::uint64_t{layout.fragment_code(f.depth, f.coverage)} << 32 | data);
  }
  std::optional<PixelDepth> deepest;
  for (auto& [index, records] : deep) {
    std::sort(records.begin(), records.end());
    const auto distinct = static_cast<std::uint64_t>(std::unique(records.begin(), records.end()) - records.begin());
    if (distinct > limit && (!deepest || distinct > deepest->records))
      deepest = PixelDepth{{static_cast<std::uint32_t>(index % screen.x), static_cast<std::uint32_t>(index / screen.x)},
                           distinct, true};
  }
  return deepest;
}

std::optional<PixelDepth> pixel_counted_beyond(std::span<const std::uint32_t> counts, Extent screen,
                                               std::uint64_t limit) {
  const auto deepest = std::max_element(counts.begin(), counts.end());
  if (deepest == counts.end() || *deepest <= limit) return std::nullopt;
  const auto index = static_cast<std::uint64_t>(deepest - counts.begin());
  return PixelDepth{{static_cast<std::uint32_t>(index % screen.x), static_cast<std::uint32_t>(index / screen.x)},
                    *deepest, false};
}

std::optional<std::uint32_t> age_bits_for(std::uint64_t records) {
  for (std::uint32_t a = HABUFFER_MIN_AGE_BITS; a <= HABUFFER_MAX_AGE_BITS; ++a)
    if (records <= (std::uint64_t{1} << a) - 1) return a;
  return std::nullopt;
}

bool counted_depth_bounds_growth(Technique t, const BufferConfig& c) {
  return uses_table(t) && c.early_cull_tau <= 0.0f;
}

std::string too_deep_message(const PixelDepth& d, std::uint32_t age_bits, OptionSpelling spelling) {
  std::string m = "pixel (" + std::to_string(d.pixel.x) + ", " + std::to_string(d.pixel.y) + ") has " +
                  std::to_string(d.records) + (d.distinct ? " distinct fragments" : " fragments (duplicates included)") + ", more than AMAX = 2^" + std::to_string(age_bits) +
                  " - 1 = " + std::to_string((1u << age_bits) - 1) + ", at any table size: ";
  if (const std::optional<std::uint32_t> a = age_bits_for(d.records))
    return m + "use " + option_value("age-bits", std::to_string(*a), spelling) + " (or accept the loss)";
  return m + "no age bits hold it (at most " + std::to_string(HABUFFER_MAX_AGE_BITS) +
         "): use another technique, such as lists (or accept the loss)";
}

}  // namespace habuffer
