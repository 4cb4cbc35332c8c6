#include "habuffer/memory_model.h"

#include "habuffer/technique_descriptor.h"

namespace habuffer {

std::uint64_t memory_model_bytes(const TechniqueConfig& c, std::uint64_t capacity) {
  return descriptor(c.technique).memory_bytes(c, capacity);
}

std::uint64_t memory_model_bytes(const FragmentBuffer& buffer) {
  return memory_model_bytes(buffer.technique_config(), buffer.capacity());
}

double paper_memory_bytes(Technique technique, std::uint64_t pixels, std::uint64_t fragments, double load,
                          std::uint32_t layers) {
  return descriptor(technique).paper_memory_bytes(pixels, fragments, load, layers);
}

double paper_paged_lists_bytes(std::uint64_t pixels, std::uint64_t fragments, std::uint32_t page) {
  const double k = static_cast<double>(page);
  return (40.0 * static_cast<double>(pixels) + static_cast<double>(fragments) / k * (56.0 * k + 32.0)) / 8.0;
}

}  // namespace habuffer
