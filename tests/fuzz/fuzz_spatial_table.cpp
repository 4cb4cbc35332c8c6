// libFuzzer target: the spatial hash's table file (habuffer/spatial_hash_file.h).
// Any input must either load or raise DataError naming the file; never
// crash, hang, allocate beyond the input's size or throw anything else. A
// table that loads must find every key it lists, with its value.
#include <cstddef>
#include <cstdint>
#include <string>

#include "habuffer/csv.h"
#include "habuffer/spatial_hash_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace habuffer;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const spatial::SpatialHash table = spatial::parse_spatial_hash(bytes, "fuzz.tab");
    const spatial::SpatialHashView view = table.view();
    for (const spatial::Entry& e : table.entries())
      if (view.find(e.key) != e.value) __builtin_trap();  // restore checked every record's lookup
  } catch (const DataError&) {
  }
  return 0;
}
