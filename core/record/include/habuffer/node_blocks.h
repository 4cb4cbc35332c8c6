/// @file
/// The lists' node pool handed to CPU threads in blocks: a thread reserves a
/// block of nodes with one atomic and fills it alone, instead of one atomic
/// add on a shared counter per fragment. A GPU's L2 atomics make one counter
/// cheap; on a CPU its cache line (and the neighbouring nodes two threads
/// would write) ping-pongs between cores, which made two threads 3-7x
/// slower than one (issue 26).
///
/// Exactness (SPEC invariant 1, pool-full rule): a fragment is dropped only
/// when every node of the pool holds a record, as with one counter. A thread
/// whose block is used up when the pool has no block left sets its fragment
/// aside; after the threads join, set-aside fragments take the nodes left in
/// other threads' blocks, on one thread, and only then are dropped. Nodes a
/// call leaves in its blocks become spare ranges that later calls hand out
/// first, so no node is lost between calls either.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace habuffer {

/// Nodes [begin, end) of a pool.
struct NodeRange {
  std::uint32_t begin = 0;  ///< first node
  std::uint32_t end = 0;    ///< one past the last node
  /// Whether the range holds no node.
  [[nodiscard]] bool empty() const { return begin == end; }
  /// Memberwise equality.
  friend bool operator==(const NodeRange&, const NodeRange&) = default;
};

/// The nodes one insert call hands out in blocks: the spare ranges earlier
/// calls left first, then fresh nodes past the pool's counter (never beyond
/// the capacity, so the counter never wraps).
class NodePool {
 public:
  /// Nodes per block: enough that reserving one is rare (one atomic per
  /// block), few enough that a block's nodes stay near each other.
  static constexpr std::uint32_t kBlock = 1024;

  /// Hands out `spare` (kept alive by the caller), then nodes from `*fresh`
  /// (the first node never handed out, updated here) up to `capacity`, in
  /// blocks of at most `block` nodes.
  NodePool(std::uint32_t* fresh, std::uint32_t capacity, std::span<const NodeRange> spare,
           std::uint32_t block = kBlock)
      : fresh_(fresh), capacity_(capacity), block_(block), spare_(spare) {}

  /// A block of nodes no other thread holds; empty when the pool has none
  /// left. Atomic always: threads that own their pixels share the pool.
  NodeRange take() {
    if (spare_taken_.load(std::memory_order_relaxed) < spare_.size()) {
      const std::size_t s = spare_taken_.fetch_add(1, std::memory_order_relaxed);
      if (s < spare_.size()) return spare_[s];
    }
    std::atomic_ref<std::uint32_t> counter(*fresh_);
    std::uint32_t old = counter.load(std::memory_order_relaxed);
    do {
      if (old >= capacity_) return {};
    } while (!counter.compare_exchange_weak(old, old + std::min(block_, capacity_ - old), std::memory_order_relaxed));
    return {old, old + std::min(block_, capacity_ - old)};
  }

  /// The nodes not handed out, with those left in `blocks` (the threads'
  /// blocks): what a call leaves (call after the threads join).
  [[nodiscard]] std::vector<NodeRange> unused(std::span<const NodeRange> blocks) const {
    std::vector<NodeRange> left;
    for (std::size_t s = std::min(spare_taken_.load(std::memory_order_relaxed), spare_.size()); s < spare_.size(); ++s)
      left.push_back(spare_[s]);
    for (const NodeRange& b : blocks)
      if (!b.empty()) left.push_back(b);
    return left;
  }

 private:
  std::uint32_t* fresh_;
  std::uint32_t capacity_;
  std::uint32_t block_;
  std::span<const NodeRange> spare_;
  std::atomic<std::size_t> spare_taken_{0};  ///< spare ranges handed out (may count past the end)
};

/// Drops empty ranges from `spare` and gives the range that ends at `*fresh`
/// back to the counter (repeatedly), so a call on one thread leaves the pool
/// as one counter would: nodes [0, *fresh) handed out, no spare range.
inline void return_to_counter(std::vector<NodeRange>& spare, std::uint32_t* fresh) {
  std::erase_if(spare, [](const NodeRange& r) { return r.empty(); });
  for (bool returned = true; returned;) {
    const auto last = std::find_if(spare.begin(), spare.end(), [&](const NodeRange& r) { return r.end == *fresh; });
    returned = last != spare.end();
    if (returned) {
      *fresh = last->begin;
      spare.erase(last);
    }
  }
}

}  // namespace habuffer
