#include "late_readback.h"

#include <chrono>
#include <string>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {

LateReadback::~LateReadback() {
  for (Slot& s : pending_) release(s);
  for (Slot& s : free_) release(s);
  if (current_) release(*current_);
}

void LateReadback::release(Slot& slot) {
  if (!slot.made_on.current()) return;  // another context's names are not ours to delete (gl_context.h)
  if (slot.fence) glDeleteSync(slot.fence);
  slot.fence = nullptr;
  if (slot.queries[0]) glDeleteQueries(kMarks, slot.queries);
  for (GLuint& q : slot.queries) q = 0;
}

LateReadback::Slot& LateReadback::begin(std::uint64_t words) {
  if (current_) abandon();
  if (!free_.empty()) {
    current_.emplace(std::move(free_.back()));
    free_.pop_back();
  } else {
    current_.emplace();
    glCreateQueries(GL_TIMESTAMP, kMarks, current_->queries);
  }
  Slot& s = *current_;
  if (s.words.bytes() < words * 4) s.words = GlStorage(words * 4);
  s.frame = LateFrame{};
  return s;
}

void LateReadback::mark(Mark mark) { glQueryCounter(current_->queries[mark], GL_TIMESTAMP); }

void LateReadback::copy(GLuint source, std::uint64_t source_offset, std::uint64_t word, std::uint64_t bytes) {
  glCopyNamedBufferSubData(source, current_->words.id(), static_cast<GLintptr>(source_offset),
                           static_cast<GLintptr>(word * 4), static_cast<GLsizeiptr>(bytes));
}

void LateReadback::end() {
  Slot& s = *current_;
  s.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  if (!s.fence) throw GlError("glFenceSync returned no fence for the frame's readback");
  glFlush();  // the fence reaches the GPU, so it signals without anyone waiting
  pending_.push_back(std::move(s));
  current_.reset();
}

void LateReadback::abandon() {
  if (!current_) return;
  free_.push_back(std::move(*current_));
  current_.reset();
}

std::vector<LateReadback::Done> LateReadback::collect(bool wait, double timeout_ms) {
  std::vector<Done> done;
  while (!pending_.empty()) {
    Slot& s = pending_.front();
    GLenum status = glClientWaitSync(s.fence, 0, 0);
    if (wait && status == GL_TIMEOUT_EXPIRED) {
      // Bounded: a fence that never signals is a GPU that stopped.
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(timeout_ms);
      while (status == GL_TIMEOUT_EXPIRED && std::chrono::steady_clock::now() < deadline)
        status = glClientWaitSync(s.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 10'000'000);  // 10 ms
      if (status == GL_TIMEOUT_EXPIRED)
        throw GlError("frame " + std::to_string(s.frame.report.index) + "'s readback fence did not signal in " +
                      std::to_string(static_cast<long>(timeout_ms)) + " ms");
    }
    if (status == GL_WAIT_FAILED) throw GlError("glClientWaitSync failed on a frame's readback fence");
    if (status == GL_TIMEOUT_EXPIRED) break;
    Done d;
    d.words = s.words.read_words(s.words.bytes() / 4);  // the fence signalled: no wait
    GLuint64 t[kMarks] = {0, 0, 0, 0};
    for (int m = 0; m < kMarks; ++m) glGetQueryObjectui64v(s.queries[m], GL_QUERY_RESULT, &t[m]);
    for (int m = 0; m + 1 < kMarks; ++m) d.gpu_ms[m] = t[m + 1] > t[m] ? static_cast<double>(t[m + 1] - t[m]) * 1e-6 : 0.0;
    glDeleteSync(s.fence);
    s.fence = nullptr;
    d.frame = std::move(s.frame);
    free_.push_back(std::move(s));
    pending_.pop_front();
    done.push_back(std::move(d));
  }
  return done;
}

std::uint64_t LateReadback::bytes() const {
  std::uint64_t b = 0;
  for (const Slot& s : pending_) b += s.words.bytes();
  for (const Slot& s : free_) b += s.words.bytes();
  if (current_) b += current_->words.bytes();
  return b;
}

}  // namespace habuffer::gl
