#include "habuffer/build_report.h"

#include "habuffer/memory_model.h"

namespace habuffer {

BuildReport summarize(const FragmentBuffer& any, const Counters& counters) {
  BuildReport r;
  r.counters = counters;
  r.capacity = any.capacity();
  r.memory_bytes = any.memory_bytes();
  r.memory_model_bytes = memory_model_bytes(any);
  any.measure(r);
  return r;
}

}  // namespace habuffer
