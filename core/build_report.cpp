#include "habuffer/build_report.h"

#include "habuffer/ha_buffer.h"
#include "habuffer/memory_model.h"

namespace habuffer {

BuildReport summarize(const FragmentBuffer& any, const Counters& counters) {
  BuildReport r;
  r.counters = counters;
  r.capacity = any.capacity();
  r.memory_bytes = any.memory_bytes();
  r.memory_model_bytes = memory_model_bytes(any);
  const auto* ha = dynamic_cast<const HaBuffer*>(&any);
  if (ha == nullptr) {
    r.stored = any.count_stored();
    r.load_factor = r.capacity > 0 ? static_cast<double>(r.stored) / static_cast<double>(r.capacity) : 0.0;
    return r;
  }
  const HaBuffer& buffer = *ha;
  std::vector<std::uint64_t> hist = buffer.age_histogram();
  std::uint64_t weighted = 0;
  for (std::uint32_t a = 1; a < hist.size(); ++a) {
    r.stored += hist[a];
    weighted += std::uint64_t{a} * hist[a];
    if (hist[a] != 0) r.max_age = a;
  }
  hist.resize(r.max_age + 1);
  r.age_histogram = std::move(hist);
  r.load_factor = static_cast<double>(r.stored) / static_cast<double>(buffer.slot_count());
  r.mean_age = r.stored == 0 ? 0.0 : static_cast<double>(weighted) / static_cast<double>(r.stored);
  r.max_age_table_max = buffer.max_age().max();
  return r;
}

}  // namespace habuffer
