// GPU time of a span of GL commands, as the difference of two GL_TIMESTAMP
// queries. Timestamps are never "active": a host's own GL_TIME_ELAPSED query
// around a frame() or inside its gather callback keeps running untouched (a
// GL_TIME_ELAPSED query of ours would have ended the host's, GL errors
// 0x0502, or made the host's begin fail inside the gather), and spans may
// nest.
#pragma once

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/gl_context.h"

#include <chrono>
#include <utility>

namespace habuffer::gl {

class GpuTimer {
 public:
  GpuTimer() { glCreateQueries(GL_TIMESTAMP, 2, queries_); }
  ~GpuTimer() {
    if (made_on_.current()) glDeleteQueries(2, queries_);  // not another context's names (gl_context.h)
  }
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin() const { glQueryCounter(queries_[0], GL_TIMESTAMP); }
  void end() const { glQueryCounter(queries_[1], GL_TIMESTAMP); }
  // Waits for both timestamps (inside a GlStateGuard: see query_result).
  [[nodiscard]] double milliseconds() const {
    const GLuint64 start = query_result(queries_[0]), stop = query_result(queries_[1]);
    return stop > start ? static_cast<double>(stop - start) * 1e-6 : 0.0;
  }

 private:
  GLuint queries_[2] = {0, 0};
  MadeOn made_on_;
};

// Wall clock and GPU timestamps around one pass. With `finish`, the clock
// waits for the GPU (glFinish) before it starts and when it stops, so the
// wall time is the pass's whole time and none of the work queued before it
// (a fresh buffer's zeroing, a host's pass). Nothing stays active, so a pass
// that throws needs no clean-up.
class PassClock {
 public:
  PassClock(const GpuTimer& timer, bool finish) : timer_(timer), finish_(finish), start_(started(finish)) {
    timer_.begin();
  }
  PassClock(const PassClock&) = delete;
  PassClock& operator=(const PassClock&) = delete;
  // Ends the pass: {wall ms, GPU ms}.
  [[nodiscard]] std::pair<double, double> stop() {
    timer_.end();
    if (finish_) glFinish();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return {wall, timer_.milliseconds()};
  }

 private:
  static std::chrono::steady_clock::time_point started(bool finish) {
    if (finish) glFinish();
    return std::chrono::steady_clock::now();
  }

  const GpuTimer& timer_;
  bool finish_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace habuffer::gl
