// Adaptive sizing on the GPU path as an engine lives with it (issue 45):
// jumps of depth complexity lossless in one regather sized by the failed
// gather's own count (Readback::Immediate), a Deferred frame that never
// waits for the GPU (every read-back behind a signalled fence, checked by
// intercepting the calls that wait), sizing from complete counts only, and
// memory given back in one decision after a drop.
#include <gtest/gtest.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"
#include "habuffer/lossless_build.h"

namespace habuffer {
namespace {

using test::gl_context;

std::vector<gl::AtomicMode> modes() { return gl::runnable_atomic_modes(gl::query_gl_info()); }

std::vector<Fragment> layers_of(Extent screen, std::uint32_t layers, std::uint32_t seed) {
  return layered_stream(screen, layers, seed);
}

// --- the calls that make the CPU wait for the GPU, intercepted through
// libepoxy's dispatch pointers.
struct SyncLog {
  int finishes = 0;          // glFinish
  int waits = 0;             // glClientWaitSync with a timeout (a wait)
  int unfenced_reads = 0;    // buffer or query read-backs with no signalled fence before them
  int fenced_reads = 0;      // read-backs after a fence signalled
  bool fence_signalled = false;
};
SyncLog g_log;

// A hook of a void GL function: `body`, then the real call (taken from
// eglGetProcAddress, so libepoxy's lazy resolver never sees the hook).
#define HB_HOOK(name, params, args, body)                                       \
  decltype(epoxy_##name) g_real_##name = nullptr;                               \
  void EPOXY_CALLSPEC hook_##name params {                                      \
    body;                                                                       \
    g_real_##name args;                                                         \
  }

bool query_to_buffer() {
  GLint bound = 0;
  glGetIntegerv(GL_QUERY_BUFFER_BINDING, &bound);
  return bound != 0;  // the result goes to a buffer on the GPU: no wait
}

void count_read() { (g_log.fence_signalled ? g_log.fenced_reads : g_log.unfenced_reads)++; }

HB_HOOK(glFinish, (), (), ++g_log.finishes)
HB_HOOK(glGetNamedBufferSubData, (GLuint b, GLintptr o, GLsizeiptr n, void* d), (b, o, n, d), count_read())
HB_HOOK(glGetBufferSubData, (GLenum t, GLintptr o, GLsizeiptr n, void* d), (t, o, n, d), count_read())
// A query result read into client memory (not into a bound query buffer,
// not the non-blocking availability) waits for the query.
void count_query_read(GLenum pname) {
  if (pname != GL_QUERY_RESULT_AVAILABLE && !query_to_buffer()) count_read();
}
HB_HOOK(glGetQueryObjectui64v, (GLuint q, GLenum p, GLuint64* v), (q, p, v), count_query_read(p))
HB_HOOK(glGetQueryObjectuiv, (GLuint q, GLenum p, GLuint* v), (q, p, v), count_query_read(p))
HB_HOOK(glGetQueryObjectiv, (GLuint q, GLenum p, GLint* v), (q, p, v), count_query_read(p))
HB_HOOK(glGetQueryObjecti64v, (GLuint q, GLenum p, GLint64* v), (q, p, v), count_query_read(p))
decltype(epoxy_glMapNamedBufferRange) g_real_glMapNamedBufferRange = nullptr;
void* EPOXY_CALLSPEC hook_glMapNamedBufferRange(GLuint b, GLintptr o, GLsizeiptr n, GLbitfield a) {
  count_read();
  return g_real_glMapNamedBufferRange(b, o, n, a);
}

// glClientWaitSync: a wait when given a timeout; its answer says whether
// the reads after it are behind a signalled fence.
decltype(epoxy_glClientWaitSync) g_real_glClientWaitSync = nullptr;
GLenum EPOXY_CALLSPEC hook_glClientWaitSync(GLsync s, GLbitfield f, GLuint64 timeout) {
  if (timeout != 0) ++g_log.waits;
  const GLenum r = g_real_glClientWaitSync(s, f, timeout);
  g_log.fence_signalled = r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
  return r;
}

// Every hooked function, once.
#define HB_HOOKED(X)                                                                                   \
  X(glFinish) X(glGetNamedBufferSubData) X(glGetBufferSubData) X(glGetQueryObjectui64v) X(glGetQueryObjectuiv) \
  X(glGetQueryObjectiv) X(glGetQueryObjecti64v) X(glMapNamedBufferRange) X(glClientWaitSync)

// Points libepoxy's `pointer` at `hook`, keeping what it was in `saved` and
// the real function (from EGL, never libepoxy's lazy resolver) in `real`.
template <class F>
void install(F& saved, F& real, F& pointer, F hook, const char* name) {
  saved = pointer;
  real = reinterpret_cast<F>(eglGetProcAddress(name));
  if (!real) throw std::runtime_error(std::string("eglGetProcAddress(") + name + ") returned nothing");
  pointer = hook;
}

// Installs the hooks for one scope and takes them out after.
class SyncCalls {
 public:
  SyncCalls() {
    g_log = {};
#define HB_INSTALL(name) install(saved_##name, g_real_##name, epoxy_##name, hook_##name, #name);
    HB_HOOKED(HB_INSTALL)
  }
  ~SyncCalls() {
#define HB_REMOVE(name) epoxy_##name = saved_##name;
    HB_HOOKED(HB_REMOVE)
  }
  SyncCalls(const SyncCalls&) = delete;
  SyncCalls& operator=(const SyncCalls&) = delete;
  // Starts counting afresh (a frame's calls).
  void reset() { g_log = {}; }
  [[nodiscard]] const SyncLog& log() const { return g_log; }

 private:
  // libepoxy's pointers as they were, put back afterwards.
#define HB_SAVED(name) decltype(epoxy_##name) saved_##name = nullptr;
  HB_HOOKED(HB_SAVED)
};

gl::GlFrameOptions deferred() {
  gl::GlFrameOptions o;
  o.readback = gl::Readback::Deferred;
  return o;
}

// The interceptor itself: a frame with an Immediate readback does wait
// (its counters read at once), so the check can fail.
TEST(GlAdaptive, TheSyncCheckSeesTheWaitsOfAnImmediateFrame) {
  gl_context();
  const Extent screen{16, 16};
  gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(1), gl::AtomicMode::Emulated64);
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 2, 1));
  SyncCalls calls;
  (void)inserter.insert(layers_of(screen, 2, 2));
  EXPECT_GT(calls.log().unfenced_reads + calls.log().finishes, 0);
}

// Readback::Deferred: after the first frame (its counting gather, the one
// documented wait), a frame makes no glFinish, no waiting glClientWaitSync
// and no read-back that no signalled fence precedes; every frame's report
// arrives later, complete, in order, with the CPU path's counts.
TEST(GlAdaptive, ADeferredFrameNeverWaitsForTheGpuAndItsReportArrivesComplete) {
  gl_context();
  const Extent screen{24, 20};
  for (gl::AtomicMode mode : modes()) {
    SCOPED_TRACE(gl::to_string(mode));
    gl::GlHaBuffer gpu(test::config(screen, {}, test::layout_of(mode), 8), test::random_offsets(3), mode, deferred());
    EXPECT_EQ(gpu.options().readback, gl::Readback::Deferred);
    EXPECT_EQ(*gpu.options().max_attempts, 1u);
    EXPECT_FALSE(*gpu.options().finish_timing);
    gl::ComputeInserter inserter(gpu);
    std::vector<std::vector<Fragment>> streams;
    std::vector<gl::FrameReport> reports;
    const gl::FrameReport first = inserter.insert(streams.emplace_back(layers_of(screen, 3, 0)));
    ASSERT_TRUE(first.counted_fragments.has_value());
    EXPECT_FALSE(first.complete);
    SyncCalls calls;
    for (int k = 1; k <= 8; ++k) {
      calls.reset();
      const gl::FrameReport r = inserter.insert(streams.emplace_back(layers_of(screen, 3, static_cast<std::uint32_t>(k))));
      EXPECT_EQ(calls.log().finishes, 0) << "frame " << k;
      EXPECT_EQ(calls.log().waits, 0) << "frame " << k;
      EXPECT_EQ(calls.log().unfenced_reads, 0) << "frame " << k;
      EXPECT_FALSE(r.complete);
      EXPECT_EQ(r.index, static_cast<std::uint64_t>(k));
      for (const gl::FrameReport& c : r.completed) reports.push_back(c);
    }
    calls.reset();
    for (gl::FrameReport& c : gpu.finish_reports()) reports.push_back(std::move(c));
    EXPECT_EQ(gpu.frames_in_flight(), 0u);
    ASSERT_EQ(reports.size(), streams.size());
    for (std::size_t k = 0; k < reports.size(); ++k) {
      SCOPED_TRACE("frame " + std::to_string(k));
      const gl::FrameReport& r = reports[k];
      EXPECT_TRUE(r.complete);
      EXPECT_EQ(r.index, k);
      EXPECT_EQ(r.counters.fragments, streams[k].size());
      EXPECT_TRUE(r.lossless());
      EXPECT_EQ(r.counters.stored(), streams[k].size()) << "distinct depths: every fragment stored";
      ASSERT_EQ(r.attempts.size(), 1u);
      EXPECT_EQ(r.table, gpu.table());
    }
    // The lists of the last frame are the CPU path's.
    EXPECT_EQ(gpu.read_table(), test::table_words(test::cpu_twin(gpu, streams.back())));
  }
}

// A jump 0 -> 40 and 1 -> 40 layers and a drop 40 -> 1, each in one frame,
// by the default lossless driver (Readback::Immediate): the jump's frame
// takes one regather into the table for the failed gather's count, and the
// drop gives the memory back at the next frame, in one decision.
TEST(GlAdaptive, AnyJumpIsLosslessInOneRegatherAndADropGivesMemoryBackAtTheNextFrame) {
  gl_context();
  const Extent screen{32, 32};
  const ResizePolicy policy;
  for (gl::AtomicMode mode : modes()) {
    for (const int from : {0, 1}) {
      SCOPED_TRACE(gl::to_string(mode) + ", jump " + std::to_string(from) + " -> 40");
      gl::GlHaBuffer gpu(test::config(screen, {}, test::layout_of(mode), 8), test::random_offsets(5), mode);
      gl::ComputeInserter inserter(gpu);
      (void)inserter.insert(layers_of(screen, from, 1));
      const std::vector<Fragment> deep = layers_of(screen, 40, 2);
      const gl::FrameReport jump = inserter.insert(deep);
      EXPECT_TRUE(jump.lossless());
      ASSERT_EQ(jump.attempts.size(), 2u);
      EXPECT_EQ(jump.attempts[1].sized_for, deep.size()) << "every fragment the failed gather received";
      // The failed gather stopped inserting at its first failure: every
      // later call counted (failed_iter of that attempt), none lost in the end.
      EXPECT_EQ(jump.attempts[0].counters.fragments, deep.size());
      EXPECT_GT(jump.attempts[0].counters.failed_iter, deep.size() / 2);
      EXPECT_EQ(jump.skipped, 0u);
      EXPECT_EQ(jump.table, policy.grown(jump.attempts[0].table, screen, deep.size()));
      EXPECT_EQ(gpu.read_table(), test::table_words(test::cpu_twin(gpu, deep)));
      const gl::FrameReport steady = inserter.insert(layers_of(screen, 40, 3));
      EXPECT_EQ(steady.attempts.size(), 1u);
      EXPECT_FALSE(steady.resized) << "sized mid-band: no second decision";
      const gl::FrameReport drop = inserter.insert(layers_of(screen, 1, 4));
      ASSERT_TRUE(drop.sized_by.has_value());
      EXPECT_EQ(drop.sized_by->records, 40u * screen.area()) << "sized by the frame before the drop";
      EXPECT_FALSE(drop.resized);
      const gl::FrameReport after = inserter.insert(layers_of(screen, 1, 5));
      ASSERT_TRUE(after.sized_by.has_value());
      EXPECT_EQ(after.sized_by->records, screen.area());
      ASSERT_TRUE(after.resized);
      EXPECT_EQ(after.table, policy.initial_table(screen, screen.area())) << "memory back in one decision";
      EXPECT_TRUE(after.lossless());
    }
  }
}

// One gather per frame (max_attempts 1, Immediate): the jump's frame loses
// fragments, counted, and the next frame, sized from that frame's count in
// one decision, loses none.
TEST(GlAdaptive, WithOneGatherPerFrameAJumpIsLossyForItsOwnFrameOnly) {
  gl_context();
  const Extent screen{32, 32};
  gl::GlFrameOptions o;
  o.max_attempts = 1;
  gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(9), gl::AtomicMode::Emulated64, o);
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 1, 1));
  const gl::FrameReport jump = inserter.insert(layers_of(screen, 40, 2));
  EXPECT_FALSE(jump.lossless());
  EXPECT_EQ(jump.counters.fragments, 40u * screen.area()) << "every loss counted";
  const gl::FrameReport next = inserter.insert(layers_of(screen, 40, 3));
  ASSERT_TRUE(next.sized_by.has_value());
  EXPECT_EQ(next.sized_by->records, 40u * screen.area()) << "judged by what it received, not what it stored";
  EXPECT_TRUE(next.resized);
  EXPECT_TRUE(next.lossless());
  EXPECT_FALSE(inserter.insert(layers_of(screen, 40, 4)).resized) << "mid-band: no second decision";
}

// The same jump with Readback::Deferred: the jump's frames lose fragments
// (counted, reported late) only until their count arrives; the first frame
// sized by it is lossless, and no decision ever reads a partial count.
TEST(GlAdaptive, DeferredSizingDecidesFromCompleteCountsAndRecoversFromAJumpInOneDecision) {
  gl_context();
  const Extent screen{32, 32};
  const ResizePolicy policy;
  gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(7), gl::AtomicMode::Emulated64,
                     deferred());
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 1, 1));
  std::vector<gl::FrameReport> done;
  int lossy = 0, frames_to_lossless = -1;
  std::uint64_t sizing_frame = 0;
  for (int k = 1; k <= 6; ++k) {
    const gl::FrameReport r = inserter.insert(layers_of(screen, 40, static_cast<std::uint32_t>(10 + k)));
    for (const gl::FrameReport& c : r.completed) {
      done.push_back(c);
      lossy += c.lossless() ? 0 : 1;
      if (c.index >= 1 && c.lossless() && frames_to_lossless < 0) frames_to_lossless = static_cast<int>(c.index);
    }
    if (r.sized_by) {
      // A decision reads a complete frame's count: the records of a frame
      // gathered before this one, every fragment counted.
      EXPECT_LT(r.sized_by->frame, r.index);
      if (r.sized_by->frame >= 1) {
        EXPECT_EQ(r.sized_by->records, 40u * screen.area());
        if (sizing_frame == 0) {
          sizing_frame = r.index;
          EXPECT_TRUE(r.resized);
          EXPECT_EQ(r.table, policy.initial_table(screen, 40u * screen.area())) << "one decision to the count";
        }
      }
    }
  }
  for (gl::FrameReport& c : gpu.finish_reports()) {
    lossy += c.lossless() ? 0 : 1;
    if (c.lossless() && frames_to_lossless < 0) frames_to_lossless = static_cast<int>(c.index);
    done.push_back(std::move(c));
  }
  ASSERT_EQ(done.size(), 7u);
  for (const gl::FrameReport& c : done) EXPECT_EQ(c.counters.fragments, c.index == 0 ? screen.area() : 40u * screen.area());
  ASSERT_GT(sizing_frame, 0u);
  EXPECT_GE(lossy, 1) << "the jump's frame had the old table";
  EXPECT_LE(lossy, 3) << "lossy only until the count arrived";
  EXPECT_EQ(static_cast<std::uint64_t>(frames_to_lossless), sizing_frame);
}

// A pool jumps the same way (the lists' node pool sized for the nodes asked for).
TEST(GlAdaptive, AListsPoolJumpIsLosslessInOneRegather) {
  gl_context();
  const Extent screen{16, 16};
  TechniqueConfig c;
  c.technique = Technique::Lists;
  c.buffer = test::config(screen, {}, Layout::L64, 8);
  gl::GlFrameDriver gpu(gl::make_gl_technique(c, test::random_offsets(2), gl::AtomicMode::Emulated64));
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 1, 1));
  const std::vector<Fragment> deep = layers_of(screen, 40, 2);
  const gl::FrameReport jump = inserter.insert(deep);
  EXPECT_TRUE(jump.lossless());
  ASSERT_EQ(jump.attempts.size(), 2u);
  EXPECT_EQ(jump.attempts[1].sized_for, deep.size());
  EXPECT_EQ(jump.capacity, ResizePolicy{}.counted_capacity(deep.size()));
}

TEST(GlAdaptive, RequestRecountSizesTheNextFrameFromItsOwnCount) {
  gl_context();
  const Extent screen{16, 16};
  gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(2), gl::AtomicMode::Emulated64);
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 1, 1));
  EXPECT_FALSE(gpu.counts_next_frame());
  gpu.request_recount();
  EXPECT_TRUE(gpu.counts_next_frame());
  const gl::FrameReport r = inserter.insert(layers_of(screen, 30, 2));
  ASSERT_TRUE(r.counted_fragments.has_value());
  EXPECT_EQ(*r.counted_fragments, 30u * screen.area());
  EXPECT_EQ(r.attempts.size(), 1u) << "sized before it gathered";
  EXPECT_FALSE(r.sized_by.has_value()) << "the frame before the recount decides nothing";
  EXPECT_TRUE(r.lossless());
  EXPECT_EQ(r.table, ResizePolicy{}.initial_table(screen, 30u * screen.area()));
  gl::GlHaBuffer given(test::config(screen, screen, Layout::L64, 8), test::random_offsets(2), gl::AtomicMode::Emulated64);
  EXPECT_THROW(given.request_recount(), std::invalid_argument);
}

// A table the host sets is not undone by a count of a frame before it.
TEST(GlAdaptive, ATableTheHostSetsIsNotResizedByAnEarlierFramesCount) {
  gl_context();
  const Extent screen{16, 16};
  gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(2), gl::AtomicMode::Emulated64);
  gl::ComputeInserter inserter(gpu);
  (void)inserter.insert(layers_of(screen, 1, 1));
  gpu.resize({200, 200});  // load 0.0064 for the last frame's count: that count must not shrink it
  const gl::FrameReport r = inserter.insert(layers_of(screen, 1, 2));
  EXPECT_FALSE(r.sized_by.has_value());
  EXPECT_FALSE(r.resized);
  EXPECT_EQ(r.table, (Extent{200, 200}));
  const gl::FrameReport next = inserter.insert(layers_of(screen, 1, 3));
  ASSERT_TRUE(next.sized_by.has_value());
  EXPECT_TRUE(next.resized) << "its own frames' counts adapt it (an automatic table)";
}

TEST(GlAdaptive, BudgetsStopLosslessGrowthAndSaySo) {
  gl_context();
  const Extent screen{16, 16};
  const std::vector<Fragment> deep = layers_of(screen, 30, 2);
  for (const bool by_time : {false, true}) {
    SCOPED_TRACE(by_time ? "time budget" : "growth budget");
    gl::GlFrameOptions o;
    if (by_time) o.attempt_budget_ms = 1e-6;
    else o.growth_budget = 2.0;
    gl::GlHaBuffer gpu(test::config(screen, {}, Layout::L64, 8), test::random_offsets(2), gl::AtomicMode::Emulated64, o);
    gl::ComputeInserter inserter(gpu);
    (void)inserter.insert(layers_of(screen, 1, 1));
    const gl::FrameReport r = inserter.insert(deep);
    EXPECT_TRUE(r.budget_stopped);
    EXPECT_FALSE(r.lossless());
    EXPECT_EQ(r.attempts.size(), 1u);
    EXPECT_EQ(r.counters.fragments, deep.size()) << "the losses are counted as always";
  }
}

TEST(GlAdaptive, OptionsThatNeedTheFramesCountAtOnceAreRefusedWithADeferredReadback) {
  gl_context();
  const BufferConfig c = test::config({8, 8}, {}, Layout::L64, 8);
  const auto refused = [&](gl::GlFrameOptions o, const std::string& words) {
    try {
      gl::GlHaBuffer gpu(c, test::random_offsets(1), gl::AtomicMode::Emulated64, o);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  gl::GlFrameOptions o = deferred();
  o.max_attempts = 4;
  refused(o, "Readback::Immediate");
  o = deferred();
  o.capture = true;
  refused(o, "Readback::Immediate");
  o = deferred();
  o.finish_timing = true;
  refused(o, "never waits");
  o = {};
  o.growth_budget = 0.5;
  refused(o, "growth_budget");
  o = {};
  o.attempt_budget_ms = -1.0;
  refused(o, "attempt_budget_ms");
}

// Where the implementation can end a call without an outcome (llvmpipe),
// the driver counts the calls itself: a host that gives no call count
// still has every call counted.
TEST(GlAdaptive, TheDriverCountsTheCallsItselfWhereTheImplementationNeedsIt) {
  gl_context();
  const Extent screen{16, 16};
  gl::GlHaBuffer gpu(test::config(screen, screen, Layout::L64, 8), test::random_offsets(2), gl::AtomicMode::Emulated64);
  gl::ComputeInserter inserter(gpu);
  const std::vector<Fragment> f = layers_of(screen, 3, 2);
  inserter.upload(f);
  const gl::FrameReport r = gpu.frame([&] { inserter.dispatch(); });  // no call count from the host
  EXPECT_EQ(r.counters.fragments, f.size());
  if (gpu.needs_call_count())
    EXPECT_NE(gpu.module_source(gl::ShaderStage::Fragment).find("#define HABUFFER_COUNT_CALLS"), std::string::npos);
  else
    EXPECT_EQ(gpu.module_source(gl::ShaderStage::Fragment).find("HABUFFER_COUNT_CALLS\n"), std::string::npos);
}

}  // namespace
}  // namespace habuffer
