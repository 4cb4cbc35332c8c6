// libFuzzer target: the CSV parsers of SPEC 10 and offsets files. Any input
// must either parse or raise DataError naming the file; never crash, hang or
// throw anything else. Parsed offsets are then validated like the CLI does.
#include <cstddef>
#include <cstdint>
#include <string>

#include "habuffer/interchange.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace habuffer;
  if (size < 3) return 0;
  const Extent screen{1u + data[1] % 64, 1u + data[2] % 64};
  std::string text(reinterpret_cast<const char*>(data + 3), size - 3);
  try {
    CsvReader in = CsvReader::from_text("fuzz.csv", std::move(text));
    if (data[0] & 1) {
      for (const Fragment& f : parse_fragments(in, screen))
        if (f.x >= screen.x || f.y >= screen.y) __builtin_trap();  // the parser must reject off-screen pixels
    } else {
      const auto rows = parse_offset_rows(in);
      try {
        (void)OffsetSequence::from_list(screen, 15, rows);
      } catch (const std::invalid_argument&) {
      }
    }
  } catch (const DataError&) {
  }
  return 0;
}
