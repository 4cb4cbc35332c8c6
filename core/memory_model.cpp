#include "habuffer/memory_model.h"

#include "habuffer/max_age_table.h"

namespace habuffer {

std::uint64_t memory_model_bytes(const TechniqueConfig& c, std::uint64_t capacity) {
  const std::uint64_t pixels = c.buffer.screen.area();
  const std::uint64_t saturation = c.buffer.saturation ? pixels * 4 : 0;  // a code per pixel
  switch (c.technique) {
    case Technique::Ha: {
      const RecordLayout layout = c.buffer.record_layout();
      const Extent cells = MaxAgeTable(c.buffer.screen, c.buffer.block).cells();
      return capacity * layout.word_bytes() + cells.area() * 4 + std::uint64_t{layout.max_age()} * 8 + saturation;
    }
    case Technique::Lists:
    case Technique::SortedLists: return pixels * 4 + capacity * 12 + 4 + saturation;
    case Technique::Arrays: return pixels * 4 + std::uint64_t{c.layers} * pixels * 8 + 4;
    case Technique::KBuffer: {
      const std::uint64_t occupancy = c.occupancy ? pixels * (std::uint64_t{c.occupancy_words} + 1) * 4 : 0;
      return std::uint64_t{c.layers} * pixels * c.buffer.record_layout().word_bytes() + occupancy;
    }
    case Technique::Wboit: return pixels * 20;
    case Technique::Blend: return pixels * 16;
  }
  return 0;
}

std::uint64_t memory_model_bytes(const FragmentBuffer& buffer) {
  return memory_model_bytes(buffer.technique_config(), buffer.capacity());
}

double paper_memory_bytes(Technique technique, std::uint64_t pixels, std::uint64_t fragments, double load,
                          std::uint32_t layers) {
  const double v = static_cast<double>(pixels), f = static_cast<double>(fragments);
  switch (technique) {
    case Technique::Ha: return (v / 8.0 + 64.0 * f / load) / 8.0;
    case Technique::Lists:
    case Technique::SortedLists: return (32.0 * v + 88.0 * f) / 8.0;
    case Technique::Arrays: return (32.0 * v + 56.0 * static_cast<double>(layers) * v) / 8.0;
    // Not in seed 000's table: the arrays' records without their counter;
    // McGuire and Bavoil's RGBA32F + R32F targets; one RGBA32F target.
    case Technique::KBuffer: return 56.0 * static_cast<double>(layers) * v / 8.0;
    case Technique::Wboit: return 20.0 * v;
    case Technique::Blend: return 16.0 * v;
  }
  return 0.0;
}

double paper_paged_lists_bytes(std::uint64_t pixels, std::uint64_t fragments, std::uint32_t page) {
  const double k = static_cast<double>(page);
  return (40.0 * static_cast<double>(pixels) + static_cast<double>(fragments) / k * (56.0 * k + 32.0)) / 8.0;
}

}  // namespace habuffer
