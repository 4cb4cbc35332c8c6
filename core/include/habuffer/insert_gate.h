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

#include <mutex>
#include <shared_mutex>

namespace habuffer {

/// One container's guard over the calls that change it (see above). Copying
/// a container gives the copy a fresh gate (no call may run on the source
/// meanwhile, as for any object being copied).
class InsertGate {
 public:
  /// An open gate.
  InsertGate() = default;
  /// A fresh gate: the source's holders stay the source's.
  InsertGate(const InsertGate&) noexcept {}
  /// Keeps this gate: the source's holders stay the source's.
  InsertGate& operator=(const InsertGate&) noexcept { return *this; }

  /// Held alone: waits until no other call holds the gate.
  [[nodiscard]] std::unique_lock<std::shared_mutex> alone() { return std::unique_lock(mutex_); }
  /// Held alone if no other call holds the gate now; else an empty lock
  /// (owns_lock() false) at once.
  [[nodiscard]] std::unique_lock<std::shared_mutex> alone_if_free() {
    return std::unique_lock(mutex_, std::try_to_lock);
  }
  /// Held with other shared holders: waits while a call holds it alone.
  [[nodiscard]] std::shared_lock<std::shared_mutex> shared() { return std::shared_lock(mutex_); }

 private:
  std::shared_mutex mutex_;
};

}  // namespace habuffer
