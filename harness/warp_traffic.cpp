#include "habuffer/harness/warp_traffic.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

namespace habuffer::harness {

TrafficCounts& TrafficCounts::operator+=(const TrafficCounts& o) {
  warps += o.warps;
  lanes += o.lanes;
  instructions += o.instructions;
  accesses += o.accesses;
  sectors += o.sectors;
  lines += o.lines;
  atomics += o.atomics;
  conflicts += o.conflicts;
  chain += o.chain;
  chain_max = std::max(chain_max, o.chain_max);
  return *this;
}

void WarpRecorder::begin_lane(std::uint32_t lane) {
  if (lane >= kLanes) throw std::out_of_range("lane " + std::to_string(lane) + " of a warp of 32");
  lane_ = lane;
  lanes_begun_ |= 1u << lane;
}

void WarpRecorder::record(std::uint16_t site, std::uint64_t address, AccessKind kind, bool waits) {
  lanes_[lane_].push_back({address, site, kind});
  if (waits) ++chain_[lane_];
}

namespace {

// Distinct values of `v` (sorted in place).
std::uint64_t distinct(std::vector<std::uint64_t>& v) {
  std::sort(v.begin(), v.end());
  return static_cast<std::uint64_t>(std::unique(v.begin(), v.end()) - v.begin());
}

}  // namespace

void WarpRecorder::end_warp() {
  if (lanes_begun_ == 0) return;
  std::size_t steps = 0;
  std::uint32_t chain = 0;
  for (std::uint32_t l = 0; l < kLanes; ++l) {
    steps = std::max(steps, lanes_[l].size());
    chain = std::max(chain, chain_[l]);
    counts_.accesses += lanes_[l].size();
  }
  counts_.warps += 1;
  counts_.lanes += static_cast<std::uint64_t>(std::popcount(lanes_begun_));
  counts_.chain += chain;
  counts_.chain_max = std::max(counts_.chain_max, chain);
  // Step i: the lanes' i-th accesses, one instruction per site among them.
  std::vector<const Access*> step;
  std::vector<std::uint64_t> sectors, lines, atomic_addresses;
  for (std::size_t i = 0; i < steps; ++i) {
    step.clear();
    for (std::uint32_t l = 0; l < kLanes; ++l)
      if (i < lanes_[l].size()) step.push_back(&lanes_[l][i]);
    std::sort(step.begin(), step.end(), [](const Access* a, const Access* b) { return a->site < b->site; });
    for (std::size_t b = 0; b < step.size();) {
      std::size_t e = b;
      sectors.clear();
      lines.clear();
      atomic_addresses.clear();
      for (; e < step.size() && step[e]->site == step[b]->site; ++e) {
        sectors.push_back(step[e]->address >> 5);
        lines.push_back(step[e]->address >> 7);
        if (step[e]->kind == AccessKind::Atomic || step[e]->kind == AccessKind::Reduction)
          atomic_addresses.push_back(step[e]->address);
      }
      counts_.instructions += 1;
      counts_.sectors += distinct(sectors);
      counts_.lines += distinct(lines);
      counts_.atomics += atomic_addresses.size();
      const std::uint64_t n = atomic_addresses.size();
      counts_.conflicts += n - distinct(atomic_addresses);
      b = e;
    }
  }
  for (auto& l : lanes_) l.clear();
  chain_.fill(0);
  lanes_begun_ = 0;
}

}  // namespace habuffer::harness
