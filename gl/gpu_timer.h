// GPU time of a span of GL commands (GL_TIME_ELAPSED query). Only one such
// query may be active at a time, so spans must not nest.
#pragma once

#include <epoxy/gl.h>

namespace habuffer::gl {

class GpuTimer {
 public:
  GpuTimer() { glCreateQueries(GL_TIME_ELAPSED, 1, &query_); }
  ~GpuTimer() { glDeleteQueries(1, &query_); }
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin() const { glBeginQuery(GL_TIME_ELAPSED, query_); }
  void end() const { glEndQuery(GL_TIME_ELAPSED); }
  // Waits for the result.
  [[nodiscard]] double milliseconds() const {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
    return static_cast<double>(ns) * 1e-6;
  }

 private:
  GLuint query_ = 0;
};

}  // namespace habuffer::gl
