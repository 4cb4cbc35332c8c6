#include "ply_check.h"

#include <sys/stat.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "habuffer/scene.h"

namespace habuffer {
namespace {

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t min_row_bytes = 0;  // binary: scalars plus list lengths (lists may be empty)
};

// Bytes of a PLY scalar type, 0 when unknown.
std::uint64_t scalar_bytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// Beyond any mesh this library renders, and small enough that the sums
// below cannot overflow.
constexpr std::uint64_t kMaxRows = std::uint64_t{1} << 32;

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw SceneError("mesh file '" + path + "': " + why);
}

// A header line is a keyword and a few words: a longer one is not a PLY header
// (binary data after a "ply" line), refused before it fills memory.
constexpr std::size_t kMaxHeaderLine = std::size_t{1} << 16;

// The next line (without its newline) into `line`; false at the end of the stream.
bool header_line(std::istream& in, std::string& line, const std::string& path) {
  line.clear();
  std::streambuf& b = *in.rdbuf();
  for (;;) {
    const int c = b.sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return !line.empty();
    }
    if (c == '\n') return true;
    if (line.size() == kMaxHeaderLine)
      refuse(path, "PLY header line longer than " + std::to_string(kMaxHeaderLine) + " bytes (binary data?)");
    line.push_back(static_cast<char>(c));
  }
}

bool regular_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

struct Header {
  bool ascii = false;
  std::vector<Element> elements;
  std::uint64_t data_offset = 0;
};

Header read_header(std::istream& in, const std::string& path) {
  Header h;
  std::string line;
  bool format = false;
  for (int n = 0; header_line(in, line, path); ++n) {
    if (n > 10000) refuse(path, "PLY header has no end_header in its first 10000 lines");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (n == 0) {
      if (keyword != "ply") refuse(path, "not a PLY file (no 'ply' line)");
      continue;
    }
    if (keyword == "end_header") {
      if (!format) refuse(path, "PLY header has no format line");
      const std::streamoff offset = in.tellg();
      if (offset < 0) refuse(path, "PLY data cannot be located after its header");
      h.data_offset = static_cast<std::uint64_t>(offset);
      return h;
    }
    if (keyword == "format") {
      std::string kind;
      words >> kind;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
        refuse(path, "PLY format '" + kind + "' is not ascii, binary_little_endian or binary_big_endian");
      h.ascii = kind == "ascii";
      format = true;
    } else if (keyword == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      try {
        std::size_t used = 0;
        e.count = std::stoull(count, &used);
        if (used != count.size() || count.front() == '-') throw std::invalid_argument(count);
      } catch (const std::exception&) {
        refuse(path, "PLY element '" + e.name + "' has count '" + count + "', not a non-negative integer");
      }
      if (e.count > kMaxRows)
        refuse(path, "PLY element '" + e.name + "' claims " + std::to_string(e.count) + " rows, more than 2^32");
      h.elements.push_back(e);
    } else if (keyword == "property") {
      if (h.elements.empty()) refuse(path, "PLY property before any element");
      std::string type;
      words >> type;
      const std::uint64_t bytes = type == "list" ? [&] {
        std::string count_type;
        words >> count_type;
        return scalar_bytes(count_type);
      }() : scalar_bytes(type);
      if (bytes == 0) refuse(path, "PLY property of element '" + h.elements.back().name + "' has an unknown type");
      h.elements.back().min_row_bytes += bytes;
    }
  }
  refuse(path, "PLY header has no end_header");
}

}  // namespace

bool is_ply_file(const std::string& path) {
  if (!regular_file(path)) return false;  // a pipe is read once, by the loader; a device never
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && std::string(magic, 3) == "ply" && (magic[3] == '\n' || magic[3] == '\r');
}

void check_ply_file(const std::string& path) {
  if (!regular_file(path)) refuse(path, "is not a regular file (a PLY file is checked, then read again)");
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, "cannot be opened");
  check_ply_stream(in, path);
}

void check_ply_stream(std::istream& in, const std::string& path) {
  const Header h = read_header(in, path);
  if (h.ascii) {
    // One row a line; blank lines hold none. Read only as far as needed.
    std::uint64_t rows = 0;
    for (const Element& e : h.elements) rows += e.count;
    // Counted byte by byte: a line is never held, however long.
    std::uint64_t lines = 0;
    bool content = false;
    std::streambuf& b = *in.rdbuf();
    while (lines < rows) {
      const int c = b.sbumpc();
      if (c == std::char_traits<char>::eof()) {
        lines += content ? 1 : 0;
        break;
      }
      if (c == '\n') {
        lines += content ? 1 : 0;
        content = false;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        content = true;
      }
    }
    if (lines < rows)
      refuse(path, "PLY header declares " + std::to_string(rows) + " rows but the file has " + std::to_string(lines) +
                       " lines of data (truncated?)");
    return;
  }
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) refuse(path, "the size of the PLY data cannot be read");
  const auto size = static_cast<std::uint64_t>(end);
  const std::uint64_t held = size > h.data_offset ? size - h.data_offset : 0;
  std::uint64_t needed = 0;
  for (const Element& e : h.elements) {
    needed += e.count * e.min_row_bytes;
    if (needed > held)
      refuse(path, "PLY element '" + e.name + "' claims " + std::to_string(e.count) + " rows of at least " +
                       std::to_string(e.min_row_bytes) + " bytes, but the file holds " + std::to_string(held) +
                       " bytes after its header (truncated?)");
  }
}

}  // namespace habuffer
