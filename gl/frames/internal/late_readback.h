// The ring of readbacks behind Readback::Deferred (frame_report.h): each
// frame's counter words (and the words the driver adds: the deferred-call
// counts of its resume rounds) copied on the GPU into a buffer of the
// frame's own, four GL_TIMESTAMP queries around its passes, and a fence
// after them; a slot is read only once its fence has signalled, so reading
// it never waits. Slots are reused once read; the ring grows while the GPU
// is further behind (a driver throttles the CPU long before that matters).
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_context.h"

namespace habuffer::gl {

// The timestamps of a frame in flight (LateReadback::Mark).
inline constexpr int kLateMarks = 4;

// What was known of a frame when it was submitted.
struct LateFrame {
  FrameReport report;              // the submitted frame's report (sizes, sizing, index)
  std::uint64_t capacity = 0;      // the container's records at the gather
  std::uint64_t deferred_capacity = 0;  // the deferred-call buffer's capacity at the gather
  std::uint32_t rounds = 0;        // resume rounds recorded (their counts follow the counters)
  bool sorted = false;             // the Sort passes ran
  double submit_ms = 0.0;          // wall time of the submission
};
// A frame in flight: what was known of it, and its GPU copies (reused).
struct LateSlot {
  LateFrame frame;
  GlStorage words;                 // counter words, then the deferral counts
  GLuint queries[kLateMarks] = {0, 0, 0, 0};
  GLsync fence = nullptr;
  MadeOn made_on;
};
// A frame read back: what was known of it, its words and GPU times.
struct LateDone {
  LateFrame frame;
  std::vector<std::uint32_t> words;
  double gpu_ms[kLateMarks - 1] = {0, 0, 0};  // reset, gather (resume rounds in it), sort
};

class LateReadback {
 public:
  using Slot = LateSlot;
  using Done = LateDone;

  // Where a frame stands when its timestamps are taken.
  enum Mark : int { FrameBegin = 0, GatherBegin = 1, GatherEnd = 2, FrameEnd = 3, kMarks = kLateMarks };

  LateReadback() = default;
  ~LateReadback();
  LateReadback(const LateReadback&) = delete;
  LateReadback& operator=(const LateReadback&) = delete;

  // A slot for the next frame, with room for `words` words (reused when it
  // fits); the caller fills its `frame` before end().
  Slot& begin(std::uint64_t words);
  // The current slot's timestamp `mark`.
  void mark(Mark mark);
  // Copies `bytes` of `source` at `source_offset` into the current slot at word `word`.
  void copy(GLuint source, std::uint64_t source_offset, std::uint64_t word, std::uint64_t bytes);
  // Ends the current slot: its fence, flushed so it signals without a wait.
  void end();
  // Drops the current slot (a frame that threw before end()).
  void abandon();

  // The slots whose fence has signalled, oldest first, stopping at the first
  // that has not (frames complete in order). With `wait`, waits for every
  // slot, at most `timeout_ms` each (GlError beyond: the GPU is stuck).
  std::vector<Done> collect(bool wait, double timeout_ms = 10000.0);
  // Frames in flight.
  [[nodiscard]] std::size_t pending() const { return pending_.size(); }
  // Bytes of every slot's buffer.
  [[nodiscard]] std::uint64_t bytes() const;

 private:
  static void release(Slot& slot);
  std::deque<Slot> pending_;
  std::vector<Slot> free_;
  std::optional<Slot> current_;
};

}  // namespace habuffer::gl
