/// @file
/// Progress of long work on a terminal: a small bar with the rate and the time
/// left, redrawn at most ten times a second on stderr, and nothing at all when
/// stderr is not a terminal (logs and pipes stay clean) or when asked to be
/// quiet. Library loops report through a ProgressCallback.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

namespace habuffer {

/// Called with the units done so far and the total (the same unit throughout).
using ProgressCallback = std::function<void(std::uint64_t done, std::uint64_t total)>;

/// "label [#########           ]  45% 120/267 trials, 3.2/s, 46 s left":
/// `width` columns of bar; the time left is omitted until a rate is known.
std::string format_progress(const std::string& label, const std::string& unit, std::uint64_t done, std::uint64_t total,
                            double elapsed_s, int width = 20);

/// One progress line on a terminal (see the file comment).
class ProgressBar {
 public:
  /// Draws on `out` only when `enabled`; for_terminal() decides that.
  ProgressBar(std::string label, std::string unit, bool enabled, std::FILE* out = stderr);
  /// Enabled when stderr is a terminal and not `quiet`.
  static ProgressBar for_terminal(std::string label, std::string unit, bool quiet);
  ~ProgressBar();  ///< clears the line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ProgressBar(ProgressBar&&) = default;  ///< moves the line's ownership

  /// Redraws the line for `done` of `total` (at most every 100 ms, but always at done >= total).
  void update(std::uint64_t done, std::uint64_t total);
  /// A callback that calls update(); it refers to this bar, which must outlive it (and not move).
  [[nodiscard]] ProgressCallback callback();
  /// Whether it draws.
  [[nodiscard]] bool enabled() const { return enabled_; }

 private:
  std::string label_, unit_;
  bool enabled_;
  std::FILE* out_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace habuffer
