/// @file
/// How overlapping calls share one CPU container (the rule each container's
/// calls state). insert() calls may overlap on one container from any number
/// of threads: calls that share the buffers through atomics (the HA-buffer's
/// atomic insertion, and its default mode whenever another call is running)
/// run together; calls that use plain stores or pass over every pixel (a
/// serial or owner-computes HA-buffer insert, every other technique's insert,
/// clear, import_state) run alone, an overlapping call waiting for them.
/// Reading calls (list, composite, count_stored, ...) may overlap each other,
/// but not a call that changes the container.
#pragma once

#include <atomic>
#include <cstdint>

namespace habuffer {

/// One container's guard over the calls that change it (see above): a
/// reader-writer lock on one atomic word (an uncontended hold costs one
/// compare-and-swap and one store, about a third of std::shared_mutex's),
/// waiting with std::atomic::wait. Copying a container gives the copy a fresh
/// gate (no call may run on the source meanwhile, as for any object being
/// copied).
class InsertGate {
 public:
  /// One hold of the gate, released when it goes out of scope.
  class Hold {
   public:
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;
    /// Releases the hold (wakes the calls waiting for it).
    ~Hold() {
      if (gate_ == nullptr) return;
      if (alone_) {
        gate_->state_.store(0, std::memory_order_release);
        gate_->state_.notify_all();
      } else if (gate_->state_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        gate_->state_.notify_all();
      }
    }
    /// Whether the gate is held (alone_if_free may return an empty hold).
    explicit operator bool() const { return gate_ != nullptr; }

   private:
    friend class InsertGate;
    Hold(InsertGate* gate, bool alone) : gate_(gate), alone_(alone) {}
    InsertGate* gate_;
    bool alone_;
  };

  /// An open gate.
  InsertGate() = default;
  /// A fresh gate: the source's holders stay the source's.
  InsertGate(const InsertGate&) noexcept {}
  /// Keeps this gate: the source's holders stay the source's.
  InsertGate& operator=(const InsertGate&) noexcept { return *this; }

  /// Held alone: waits until no other call holds the gate.
  [[nodiscard]] Hold alone() {
    for (;;) {
      std::uint32_t seen = 0;
      if (state_.compare_exchange_weak(seen, kAlone, std::memory_order_acquire, std::memory_order_relaxed))
        return Hold(this, true);
      if (seen != 0) state_.wait(seen, std::memory_order_relaxed);
    }
  }
  /// Held alone if no other call holds the gate now; else an empty hold at once.
  [[nodiscard]] Hold alone_if_free() {
    std::uint32_t seen = 0;
    if (state_.compare_exchange_strong(seen, kAlone, std::memory_order_acquire, std::memory_order_relaxed))
      return Hold(this, true);
    return Hold(nullptr, false);
  }
  /// Held with other shared holders: waits while a call holds it alone.
  [[nodiscard]] Hold shared() {
    std::uint32_t seen = state_.load(std::memory_order_relaxed);
    for (;;) {
      if ((seen & kAlone) != 0) {
        state_.wait(seen, std::memory_order_relaxed);
        seen = state_.load(std::memory_order_relaxed);
      } else if (state_.compare_exchange_weak(seen, seen + 1, std::memory_order_acquire, std::memory_order_relaxed)) {
        return Hold(this, false);
      }
    }
  }

 private:
  static constexpr std::uint32_t kAlone = 1u << 31;  ///< held alone; else the count of shared holders
  std::atomic<std::uint32_t> state_{0};
};

}  // namespace habuffer
