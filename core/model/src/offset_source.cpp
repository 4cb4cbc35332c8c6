#include "habuffer/offset_source.h"

namespace habuffer {

OffsetSequence OffsetSource::make(Extent table, std::uint32_t count) const {
  if (generator == OffsetGenerator::List) return OffsetSequence::from_list(table, count, list);
  return OffsetSequence::make(generator, table, count, seed);
}

}  // namespace habuffer
