#include "habuffer/build_report.h"

namespace habuffer {

BuildReport summarize(const HaBuffer& buffer, const Counters& counters) {
  BuildReport r;
  r.counters = counters;
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
  r.memory_bytes = buffer.memory_bytes();
  return r;
}

}  // namespace habuffer
