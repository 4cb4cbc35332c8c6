// libFuzzer target: random small configurations and fragment streams through
// every insertion mode, checked against SPEC invariants 1-4 with a plain
// sorted-set model (std::set per pixel).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "habuffer/techniques/ha/ha_buffer.h"

namespace {

using namespace habuffer;

void check(bool ok) {
  if (!ok) __builtin_trap();
}

float depth_of(std::uint8_t b) {
  switch (b) {
    case 255: return std::numeric_limits<float>::quiet_NaN();
    case 254: return -0.5f;
    case 253: return 1.5f;
    case 252: return -0.0f;
    default: return static_cast<float>(b) / 251.0f;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 8) return 0;
  BufferConfig c;
  c.screen = {1u + data[0] % 8, 1u + data[1] % 8};
  c.table = {c.screen.x + data[2] % (c.screen.x + 1), c.screen.y + data[3] % (c.screen.y + 1)};
  c.layout = (data[4] & 1) ? Layout::L64 : Layout::L32;
  c.age_bits = 4 + (data[4] >> 1) % 3;
  c.block = 1 + (data[4] >> 3) % 4;
  c.iter_limit = (data[5] & 0x80) ? 3 + data[5] % 16 : HABUFFER_DEFAULT_ITER_LIMIT;
  const std::uint32_t mode = data[6] % 3;
  const OffsetSequence offsets = OffsetSequence::random(c.table, c.record_layout().max_age(), data[7]);

  std::vector<Fragment> frags;
  for (std::size_t i = 8; i + 3 < size; i += 4)
    frags.push_back({data[i] % c.screen.x, data[i + 1] % c.screen.y, depth_of(data[i + 2]),
                     0x01020300u | data[i + 3]});

  HaBuffer serial(c, offsets);
  const Counters n = serial.insert(frags);
  // Invariant 1: every call accounted for; the table agrees.
  check(n.fragments == frags.size());
  check(serial.count_stored() == n.stored());

  // Invariants 2 and 3: traversal finds every record once, sorted; without
  // failures the lists equal the de-duplicated input.
  const RecordLayout& l = serial.record_layout();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::set<std::pair<std::uint32_t, std::uint32_t>>> model;
  for (const Fragment& f : frags)
    if (RecordLayout::depth_valid(f.depth)) model[{f.x, f.y}].insert({l.depth_code(f.depth), l.has_data() ? f.rgba : 0});
  std::uint64_t traversed = 0;
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < c.screen.y; ++y)
    for (std::uint32_t x = 0; x < c.screen.x; ++x) {
      serial.list(x, y, list);
      traversed += list.size();
      for (std::size_t i = 1; i < list.size(); ++i)
        check(list[i - 1].code > list[i].code || (list[i - 1].code == list[i].code && list[i - 1].data > list[i].data));
      if (n.failures() == 0) {
        const auto& want = model[{x, y}];
        check(list.size() == want.size());
        auto it = want.rbegin();
        for (const ListEntry& e : list) check(e.code == it->first && e.data == (it++)->second);
      }
    }
  check(traversed == n.stored());

  // Invariant 4: reversed input, in another insertion mode and order, builds the same table.
  std::vector<Fragment> reversed(frags.rbegin(), frags.rend());
  HaBuffer other(c, offsets);
  InsertOptions o;
  o.threads = mode == 0 ? 1 : 2;
  o.mode = mode == 0 ? InsertMode::Serial : mode == 1 ? InsertMode::OwnerComputes : InsertMode::Atomic;
  o.band_rows = 1 + data[7] % 3;
  // Either order (pixel order has no owner-computes form), interleaved or
  // not, through the specialised or the shared jump-start step.
  const std::uint32_t order = (data[6] / 3) % 3;
  o.order = order == 0 || mode == 1 ? InsertOrder::Arrival : order == 1 ? InsertOrder::Pixel : InsertOrder::Auto;
  o.interleave = (data[6] & 0x40) != 0;
  o.step = (data[6] & 0x80) != 0 ? InsertStep::Shared : InsertStep::Specialised;
  const Counters m = other.insert(reversed, o);
  if (n.failed_iter + m.failed_iter == 0) {
    for (std::uint64_t s = 0; s < serial.slot_count(); ++s) check(serial.slot(s) == other.slot(s));
    check(m.stored() == n.stored());
    if (n.failures() + m.failures() == 0) check(serial.max_age().ages() == other.max_age().ages());
  }
  return 0;
}
