// GPU time of a span of GL commands (GL_TIME_ELAPSED query). Only one such
// query may be active at a time, so spans must not nest.
#pragma once

#include <epoxy/gl.h>

#include "gl_state_guard.h"

#include <chrono>
#include <utility>

namespace habuffer::gl {

class GpuTimer {
 public:
  GpuTimer() { glCreateQueries(GL_TIME_ELAPSED, 1, &query_); }
  ~GpuTimer() { glDeleteQueries(1, &query_); }
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin() const { glBeginQuery(GL_TIME_ELAPSED, query_); }
  void end() const { glEndQuery(GL_TIME_ELAPSED); }
  // Waits for the result (inside a GlStateGuard: see query_result).
  [[nodiscard]] double milliseconds() const { return static_cast<double>(query_result(query_)) * 1e-6; }

 private:
  GLuint query_ = 0;
};

// Wall clock and GPU timer around one pass; the query is ended on every
// path, so a pass that throws leaves no query active.
class PassClock {
 public:
  explicit PassClock(const GpuTimer& timer) : timer_(timer), start_(std::chrono::steady_clock::now()) { timer_.begin(); }
  ~PassClock() {
    if (running_) timer_.end();
  }
  PassClock(const PassClock&) = delete;
  PassClock& operator=(const PassClock&) = delete;
  // Ends the pass (waiting for it with glFinish when `finish`): {wall ms, GPU ms}.
  [[nodiscard]] std::pair<double, double> stop(bool finish) {
    running_ = false;
    timer_.end();
    if (finish) glFinish();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return {wall, timer_.milliseconds()};
  }

 private:
  const GpuTimer& timer_;
  std::chrono::steady_clock::time_point start_;
  bool running_ = true;
};

}  // namespace habuffer::gl
