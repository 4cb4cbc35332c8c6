#include "habuffer/probe_simulator.h"

#include <algorithm>
#include <stdexcept>

#include "habuffer/buffer_config.h"
#include "habuffer/record_layout.h"

namespace habuffer {
namespace {

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

ProbeSimulator::ProbeSimulator(const SimulatorConfig& c)
    : config_(c),
      amax_((1u << c.age_bits) - 1),
      depth_bits_(32 - c.age_bits),
      offsets_(OffsetSequence::make(c.offsets, c.table, (1u << c.age_bits) - 1, c.seed)),
      table_(c.table.area()),
      max_age_(std::size_t{(c.screen.x + c.block - 1) / c.block} * ((c.screen.y + c.block - 1) / c.block)),
      cells_x_((c.screen.x + c.block - 1) / c.block) {
  if (c.table.x < c.screen.x || c.table.y < c.screen.y)
    throw std::invalid_argument("table " + c.table.str() + " is smaller than screen " + c.screen.str());
  totals_.age_histogram.assign(amax_ + 1, 0);
}

std::uint64_t ProbeSimulator::probe(std::uint32_t pixel, std::uint32_t age) const {
  const std::uint32_t px = pixel % config_.screen.x, py = pixel / config_.screen.x;
  std::uint64_t hx = 0, hy = 0;
  if (config_.probing == Probing::Coherent) {
    hx = (px + std::uint64_t{offsets_[age - 1].x}) % config_.table.x;
    hy = (py + std::uint64_t{offsets_[age - 1].y}) % config_.table.y;
  } else {
    const std::uint64_t h = mix(config_.seed * 0x9E3779B97F4A7C15ull + (std::uint64_t{pixel} << 16) + age);
    hx = (h & 0xFFFFFFFFu) % config_.table.x;
    hy = (h >> 32) % config_.table.y;
  }
  return hx + hy * config_.table.x;
}

std::uint32_t ProbeSimulator::cell(std::uint32_t pixel) const {
  return (pixel % config_.screen.x) / config_.block + ((pixel / config_.screen.x) / config_.block) * cells_x_;
}

std::uint32_t ProbeSimulator::insert_one(std::uint32_t pixel, std::uint32_t code) {
  Entry carry{1, code, pixel};
  std::uint32_t probes = 0;
  std::uint32_t outcome = HABUFFER_STORED;
  for (;;) {
    if (carry.age > amax_) {
      outcome = HABUFFER_FAILED_AGE;
      break;
    }
    if (probes >= config_.iter_limit) {
      outcome = HABUFFER_FAILED_ITER;
      break;
    }
    ++probes;
    Entry& slot = table_[probe(carry.pixel, carry.age)];
    if (slot == carry) {
      outcome = HABUFFER_DUPLICATE;
      break;
    }
    const bool place = config_.policy == Policy::RobinHood ? slot < carry : slot.age == 0;
    if (place) {
      max_age_[cell(carry.pixel)] = std::max(max_age_[cell(carry.pixel)], carry.age);
      const Entry old = slot;
      slot = carry;
      if (old.age == 0) break;
      carry = old;  // Robin Hood only: the evicted record goes on
    }
    ++carry.age;
  }
  totals_.probes += probes;
  totals_.max_probes = std::max(totals_.max_probes, probes);
  return outcome;
}

void ProbeSimulator::insert(std::span<const Fragment> fragments) {
  const RecordLayout layout(Layout::L32, config_.age_bits);
  for (const Fragment& f : fragments) {
    if (f.x >= config_.screen.x || f.y >= config_.screen.y) throw std::out_of_range("fragment outside the screen");
    if (!RecordLayout::depth_valid(f.depth)) {
      totals_.counters.count(HABUFFER_INVALID);
      continue;
    }
    totals_.counters.count(insert_one(f.x + f.y * config_.screen.x, layout.depth_code(f.depth)));
  }
}

SimulatorTotals ProbeSimulator::totals() const {
  SimulatorTotals t = totals_;
  for (const Entry& e : table_)
    if (e.age != 0) ++t.age_histogram[e.age];
  const std::uint32_t pixels = config_.screen.x * config_.screen.y;
  for (std::uint32_t p = 0; p < pixels; ++p) {
    const std::uint32_t amax = max_age_[cell(p)];
    std::uint32_t read = 0, last_own = 0;
    for (std::uint32_t a = 1; a <= amax; ++a) {
      const Entry& e = table_[probe(p, a)];
      ++read;
      if (e.age == a && e.pixel == p) last_own = read;
      else if (config_.policy == Policy::RobinHood && e.age < a) break;  // Proposition A
    }
    t.traversal_probes += read;
    t.wasted_traversal_probes += read - last_own;
  }
  t.pixels = pixels;
  return t;
}

std::uint32_t ProbeSimulator::l32_word(std::uint64_t s) const {
  const Entry& e = table_.at(s);
  return e.age == 0 ? 0u : (e.age << depth_bits_) | e.code;
}

}  // namespace habuffer
