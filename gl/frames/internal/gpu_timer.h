// GPU time of a span of GL commands, as the difference of two GL_TIMESTAMP
// queries. Timestamps are never "active": a host's own GL_TIME_ELAPSED query
// around a frame() or inside its gather callback keeps running untouched (a
// GL_TIME_ELAPSED query of ours would have ended the host's, GL errors
// 0x0502, or made the host's begin fail inside the gather), and spans may
// nest.
#pragma once

#include <epoxy/gl.h>

#include "gl_state_guard.h"
#include "habuffer/gl/frame_report.h"
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

// How a pass is timed: whether the clock waits for the GPU around it, and
// whether it reads its GPU timestamps at once (a wait for the queries).
enum class ClockMode : std::uint8_t {
  Finish,  // glFinish before and after; GPU time read (GlFrameOptions::finish_timing)
  Read,    // no finish; GPU time read when the pass ends (waits for the timestamps)
  Unread,  // no finish, no read: wall time of submission only (Readback::Deferred never waits)
};

// The clock mode of a frame of `options` (resolved by the frame driver).
inline ClockMode clock_mode(const GlFrameOptions& options) {
  if (options.readback == Readback::Deferred) return ClockMode::Unread;
  return options.finish_timing.value_or(true) ? ClockMode::Finish : ClockMode::Read;
}

// Wall clock and GPU timestamps around one pass. With ClockMode::Finish,
// the clock waits for the GPU (glFinish) before it starts and when it
// stops, so the wall time is the pass's whole time and none of the work
// queued before it (a fresh buffer's zeroing, a host's pass); with Unread
// it neither waits nor reads (GPU time 0). Nothing stays active, so a pass
// that throws needs no clean-up.
class PassClock {
 public:
  PassClock(const GpuTimer& timer, ClockMode mode) : timer_(timer), mode_(mode), start_(started(mode)) {
    if (mode_ != ClockMode::Unread) timer_.begin();
  }
  PassClock(const PassClock&) = delete;
  PassClock& operator=(const PassClock&) = delete;
  // Ends the pass: {wall ms, GPU ms}.
  [[nodiscard]] std::pair<double, double> stop() {
    if (mode_ == ClockMode::Unread)
      return {std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count(), 0.0};
    timer_.end();
    if (mode_ == ClockMode::Finish) glFinish();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return {wall, timer_.milliseconds()};
  }

 private:
  static std::chrono::steady_clock::time_point started(ClockMode mode) {
    if (mode == ClockMode::Finish) glFinish();
    return std::chrono::steady_clock::now();
  }

  const GpuTimer& timer_;
  ClockMode mode_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace habuffer::gl
