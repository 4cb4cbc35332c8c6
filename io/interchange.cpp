#include "habuffer/interchange.h"

#include <algorithm>
#include <charconv>
#include <new>

#include "habuffer/printable.h"

namespace habuffer {

std::vector<Fragment> read_fragments(const std::string& path, Extent screen) {
  CsvReader in(path);
  return parse_fragments(in, screen);
}

std::vector<Fragment> parse_fragments(CsvReader& in, Extent screen) {
  // A multisampled stream adds the coverage word (0: the whole pixel).
  const bool covered = in.expect_header_among({{"x", "y", "depth", "rgba"}, {"x", "y", "depth", "rgba", "coverage"}}) == 1;
  std::vector<Fragment> out;
  std::vector<std::string_view> f;
  while (in.next(f)) {
    Fragment frag{in.u32(f[0], "x"), in.u32(f[1], "y"), in.f32(f[2], "depth"), in.u32_dec_or_hex(f[3], "rgba"),
                  covered ? in.u32_dec_or_hex(f[4], "coverage") : 0u};
    if (frag.x >= screen.x) in.fail("x", std::to_string(frag.x) + " outside screen " + screen.str());
    if (frag.y >= screen.y) in.fail("y", std::to_string(frag.y) + " outside screen " + screen.str());
    try {
      out.push_back(frag);
    } catch (const std::bad_alloc&) {
      in.fail("x", "out of memory after " + std::to_string(out.size()) + " fragments");
    }
  }
  return out;
}

void write_fragments(const std::string& path, std::span<const Fragment> fragments) {
  CsvWriter out(path);
  // The coverage column only where a fragment has a mask: streams of one
  // sample per pixel read and write as SPEC 10's.
  const bool covered =
      std::any_of(fragments.begin(), fragments.end(), [](const Fragment& f) { return f.coverage != 0; });
  out.text(covered ? "x,y,depth,rgba,coverage\n" : "x,y,depth,rgba\n");
  char tmp[32];
  for (const Fragment& f : fragments) {
    // Shortest text that reads back as the same float32.
    auto [end, ec] = std::to_chars(tmp, tmp + sizeof tmp, f.depth);
    (void)ec;
    out.u64(f.x).comma().u64(f.y).comma().text(std::string_view(tmp, static_cast<std::size_t>(end - tmp)));
    out.comma().hex(f.rgba, 8);
    if (covered) out.comma().hex(f.coverage, 2);
    out.endl();
  }
  out.close();
}

std::vector<glm::uvec2> read_offset_rows(const std::string& path) {
  CsvReader in(path);
  return parse_offset_rows(in);
}

std::vector<glm::uvec2> parse_offset_rows(CsvReader& in) {
  in.expect_header({"ox", "oy"});
  std::vector<glm::uvec2> rows;
  std::vector<std::string_view> f;
  while (in.next(f)) rows.emplace_back(in.u32(f[0], "ox"), in.u32(f[1], "oy"));
  return rows;
}

OffsetSequence read_offsets(const std::string& path, Extent table, std::uint32_t count) {
  const auto rows = read_offset_rows(path);
  try {
    return OffsetSequence::from_list(table, count, rows);
  } catch (const std::invalid_argument& e) {
    throw DataError(printable(path) + ": " + e.what());
  }
}

void write_offsets(const std::string& path, const OffsetSequence& offsets) {
  CsvWriter out(path);
  out.text("ox,oy\n");
  for (const auto& o : offsets.values()) out.u64(o.x).comma().u64(o.y).endl();
  out.close();
}

void write_lists(const std::string& path, const FragmentBuffer& buffer) {
  CsvWriter out(path);
  const RecordLayout layout = buffer.technique_config().buffer.record_layout();
  const std::uint32_t c = layout.coverage_bits();
  out.text(c > 0 ? "x,y,rank,code,rgba,coverage\n" : "x,y,rank,code,rgba\n");
  std::vector<ListEntry> list;
  const Extent v = buffer.screen();
  for (std::uint32_t y = 0; y < v.y; ++y)
    for (std::uint32_t x = 0; x < v.x; ++x) {
      buffer.list(x, y, list);
      for (std::size_t rank = 0; rank < list.size(); ++rank) {
        const ListEntry& e = list[rank];
        out.u64(x).comma().u64(y).comma().u64(rank).comma().u64(e.code >> c).comma().u64(e.data);
        if (c > 0) out.comma().u64(e.code & layout.coverage_mask());
        out.endl();
      }
    }
  out.close();
}

void write_table(const std::string& path, const HaBuffer& buffer) {
  CsvWriter out(path);
  out.text("slot,record\n");
  const int digits = buffer.record_layout().layout() == Layout::L64 ? 16 : 8;
  for (std::uint64_t s = 0; s < buffer.slot_count(); ++s) {
    const std::uint64_t r = buffer.slot(s);
    if (r != 0) out.u64(s).comma().hex(r, digits).endl();
  }
  out.close();
}

void write_max_age(const std::string& path, const HaBuffer& buffer) {
  CsvWriter out(path);
  out.text("cx,cy,max_age\n");
  const MaxAgeTable& m = buffer.max_age();
  for (std::uint32_t cy = 0; cy < m.cells().y; ++cy)
    for (std::uint32_t cx = 0; cx < m.cells().x; ++cx) out.u64(cx).comma().u64(cy).comma().u64(m.at(cx, cy)).endl();
  out.close();
}

}  // namespace habuffer
