#include "habuffer/gl/gl_ha_buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <tuple>

#include "clear_pass.h"
#include "compute_grid.h"
#include "gl_state_guard.h"
#include "gl_params.h"
#include "gpu_timer.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/shader_program.h"
#include "resolve_pass.h"

namespace habuffer::gl {
namespace {

constexpr std::uint64_t kCounterWords = HA_COUNTER_STRIPES * HA_COUNTER_STRIDE;
static_assert(HA_GPU_COUNTER_COUNT <= HA_COUNTER_STRIDE, "a stripe's counters fit its cache line");
constexpr std::uint64_t kAppendHeaderBytes = HA_APPEND_HEADER_WORDS * 4;
constexpr std::uint64_t kDeferredCallBytes = 32;  // std430 HaDeferred of ha_entry.glsl
static_assert(sizeof(Fragment) == 16, "captured fragments are the std430 HaFragment");

void zero_range(GLuint buffer, std::uint64_t offset, std::uint64_t bytes) {
  const GLuint z = 0;
  glClearNamedBufferSubData(buffer, GL_R32UI, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &z);
}

void delete_buffer(GLuint& b) {
  if (b != 0) glDeleteBuffers(1, &b);
  b = 0;
}

std::uint64_t max_storage_bytes() {
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  return static_cast<std::uint64_t>(bytes);
}

BufferConfig validated(BufferConfig c) {
  c.validate();
  c.table = c.table_or_screen();
  return c;
}

}  // namespace

struct GlHaBuffer::Gpu {
  GLuint table = 0, locks = 0, max_age = 0, offsets = 0, counters = 0, capture = 0, params = 0, count = 0;
  GLuint deferred[2] = {0, 0};  // ping-pong: the calls a round resumes, the calls it defers again
  std::unique_ptr<ClearPass> clear;
  std::unique_ptr<ResolvePass> resolve;
  std::unique_ptr<ShaderProgram> resume;
  GpuTimer gather_timer;
  ~Gpu() {
    for (GLuint* b : {&table, &locks, &max_age, &offsets, &counters, &capture, &params, &count, &deferred[0], &deferred[1]})
      delete_buffer(*b);
  }
};

GlHaBuffer::GlHaBuffer(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlFrameOptions& options,
                       const GlBindings& bindings)
    : config_(validated(config)),
      source_(std::move(offsets)),
      offsets_(source_.make(config_.table, config_.record_layout().max_age())),
      mode_(mode),
      options_(options),
      bindings_(bindings),
      gpu_(std::make_unique<Gpu>()) {
  options_.policy.validate();
  if (options_.max_attempts == 0) throw std::invalid_argument("at least one gather attempt is needed");
  if (options_.lock_spin_limit == 0) throw std::invalid_argument("the lock spin limit must be at least 1");
  if (options_.capture_only && !options_.capture) throw std::invalid_argument("capture_only needs capture");
  if (mode == AtomicMode::Native32 && config_.layout != Layout::L32)
    throw GlError("atomic mode native32 holds L32 records only");
  if (mode != AtomicMode::Native32 && config_.layout != Layout::L64)
    throw GlError("atomic mode " + to_string(mode) + " holds L64 records only");
  const GlInfo info = query_gl_info();
  if (mode != AtomicMode::Native32 && !info.int64_types)
    throw GlError("atomic mode " + to_string(mode) + " needs 64-bit shader types (GL_ARB_gpu_shader_int64)");
  if (mode == AtomicMode::Native64 && !info.atomic_int64)
    throw GlError("atomic mode native64 needs 64-bit shader atomics (GL_NV_shader_atomic_int64)");
  bindings_.validate();
  GLint viewport[2] = {};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  if (config_.screen.x > static_cast<std::uint32_t>(viewport[0]) || config_.screen.y > static_cast<std::uint32_t>(viewport[1]))
    throw GlError("screen " + config_.screen.str() + " exceeds this OpenGL's largest viewport " +
                  std::to_string(viewport[0]) + "x" + std::to_string(viewport[1]));
  const std::uint64_t cells = std::uint64_t{(config_.screen.x - 1) / config_.block + 1} *
                              std::uint64_t{(config_.screen.y - 1) / config_.block + 1};
  if (cells > UINT32_MAX) throw GlError("max-age table of " + std::to_string(cells) + " cells is too large");
  cells_ = static_cast<std::uint32_t>(cells);
  if (const std::string why = table_limit(config_.table); !why.empty()) throw GlError(why);
  gpu_->max_age = create_buffer(std::uint64_t{cells_} * 4);
  gpu_->counters = create_buffer(kCounterWords * 4);
  gpu_->params = create_buffer(sizeof(GlParams));
  gpu_->count = create_buffer(sizeof(std::uint64_t));
  gpu_->capture = create_buffer(kAppendHeaderBytes);
  if (options_.capture) grow_capture(std::max<std::uint64_t>(options_.capture_capacity, 1));
  grow_deferred(std::max<std::uint64_t>(options_.deferred_capacity, 1));
  allocate_table(config_.table, false);
  reset_frame_state();
  // Compile the passes now, so the first frame's timings measure the passes, not the compiler.
  gpu_->clear = std::make_unique<ClearPass>(mode_, bindings_);
  gpu_->resolve = std::make_unique<ResolvePass>(mode_, bindings_);
  gpu_->resume = std::make_unique<ShaderProgram>(
      ShaderProgram::compute(resume_compute(mode_, bindings_), "resume compute shader"));
  check_gl_errors("creating the GPU HA-buffer");
}

GlHaBuffer::~GlHaBuffer() = default;

std::string GlHaBuffer::module_source(ShaderStage stage, std::string_view header) const {
  return ha_module(mode_, bindings_, stage, header);
}

std::string GlHaBuffer::table_limit(Extent table) const {
  const std::uint64_t slots = table.area();
  if (slots > UINT32_MAX) return "the GPU path indexes at most 2^32 - 1 slots, table " + table.str();
  const std::uint64_t bytes = slots * config_.record_layout().word_bytes();
  if (bytes > max_storage_bytes())
    return "table " + table.str() + " needs " + std::to_string(bytes) + " bytes, this OpenGL allows " +
           std::to_string(max_storage_bytes()) + " per shader-storage buffer";
  return {};
}

void GlHaBuffer::allocate_table(Extent table, bool new_offsets) {
  if (const std::string why = table_limit(table); !why.empty()) throw GlError(why);
  const std::uint64_t slots = table.area();
  const std::uint64_t bytes = slots * config_.record_layout().word_bytes();
  config_.table = table;
  if (new_offsets) offsets_ = source_.make(table, config_.record_layout().max_age());
  delete_buffer(gpu_->table);
  delete_buffer(gpu_->locks);
  delete_buffer(gpu_->offsets);
  gpu_->table = create_buffer(bytes);
  zero_buffer(gpu_->table);
  if (mode_ == AtomicMode::Emulated64) {
    gpu_->locks = create_buffer(slots * 4);
    zero_buffer(gpu_->locks);  // every critical section leaves its lock at 0 again
  }
  gpu_->offsets = create_buffer(offsets_.size() * sizeof(glm::uvec2), offsets_.values().data());
  holds_frame_ = false;
  pending_count_table_.reset();  // a count in flight belongs to a table no longer in use
  write_params();
}

void GlHaBuffer::write_params() const {
  GlParams p;
  p.ha_table_size[0] = config_.table.x;
  p.ha_table_size[1] = config_.table.y;
  p.ha_age_bits = config_.age_bits;
  p.ha_block = config_.block;
  p.ha_max_age_cells_x = (config_.screen.x - 1) / config_.block + 1;
  p.ha_iter_limit = config_.iter_limit;
  p.ha_cull_tau = config_.early_cull_tau;
  p.ha_lock_spin_limit = options_.lock_spin_limit;
  p.ha_screen_size[0] = config_.screen.x;
  p.ha_screen_size[1] = config_.screen.y;
  p.ha_capture_capacity = static_cast<std::uint32_t>(capture_capacity_);
  p.ha_capture_only = options_.capture_only ? 1u : 0u;
  p.ha_count_writes = options_.count_writes ? 1u : 0u;
  p.ha_deferred_capacity = static_cast<std::uint32_t>(deferred_capacity_);
  glNamedBufferSubData(gpu_->params, 0, sizeof p, &p);
}

namespace {

// The capacity an append buffer of `item_bytes` items grows to for `needed`
// items: at least double the current one, within one shader-storage buffer
// and 32-bit counts (throws GlError naming `what` beyond that).
std::uint64_t grown_append_capacity(std::uint64_t needed, std::uint64_t current, std::uint64_t item_bytes,
                                    const std::string& what) {
  const std::uint64_t limit = std::min<std::uint64_t>((max_storage_bytes() - kAppendHeaderBytes) / item_bytes, UINT32_MAX);
  if (needed > limit)
    throw GlError(std::to_string(needed) + " " + what + " exceed this OpenGL's " + std::to_string(limit) +
                  " per shader-storage buffer");
  return std::min(limit, std::max(needed, current * 2));
}

}  // namespace

void GlHaBuffer::grow_capture(std::uint64_t needed) {
  capture_capacity_ = grown_append_capacity(needed, capture_capacity_, sizeof(Fragment), "captured fragments");
  delete_buffer(gpu_->capture);
  gpu_->capture = create_buffer(kAppendHeaderBytes + capture_capacity_ * sizeof(Fragment));
  write_params();
}

void GlHaBuffer::grow_deferred(std::uint64_t needed) {
  deferred_capacity_ = grown_append_capacity(needed, deferred_capacity_, kDeferredCallBytes, "insert calls cut short");
  for (GLuint& b : gpu_->deferred) {
    delete_buffer(b);
    b = create_buffer(kAppendHeaderBytes + deferred_capacity_ * kDeferredCallBytes);
  }
  write_params();
}

void GlHaBuffer::reset_frame_state() const {
  zero_buffer(gpu_->max_age);
  zero_buffer(gpu_->counters);
  zero_range(gpu_->capture, 0, kAppendHeaderBytes);
  zero_range(gpu_->deferred[0], 0, kAppendHeaderBytes);
}

void GlHaBuffer::bind() const {
  // glBindBufferBase also sets the generic binding of its target: keep the
  // host's, so a host that updates "its" GL_UNIFORM_BUFFER or
  // GL_SHADER_STORAGE_BUFFER inside the gather writes its own buffer.
  GLint storage_generic = 0, uniform_generic = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_generic);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_generic);
  const std::array<std::pair<unsigned, GLuint>, 7> storage{{{bindings_.table, gpu_->table},
                                                            {bindings_.max_age, gpu_->max_age},
                                                            {bindings_.offsets, gpu_->offsets},
                                                            {bindings_.counters, gpu_->counters},
                                                            {bindings_.locks, gpu_->locks},
                                                            {bindings_.capture, gpu_->capture},
                                                            {bindings_.deferred, gpu_->deferred[0]}}};
  for (const auto& [point, buffer] : storage)
    if (buffer != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, point, buffer);
  glBindBufferBase(GL_UNIFORM_BUFFER, bindings_.params, gpu_->params);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(storage_generic));
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(uniform_generic));
}

std::uint64_t GlHaBuffer::clear_pass(bool writes, PassTiming* timing, bool later) {
  bind();
  const ClearPass::Result r =
      gpu_->clear->run(config_.table, options_.clear_tile, writes, options_.finish_timing, later ? gpu_->count : 0);
  if (timing != nullptr) *timing = {r.wall_ms, r.gpu_ms};
  check_gl_errors("the clear pass");
  return r.stored;
}

void GlHaBuffer::resize(Extent table) {
  BufferConfig c = config_;
  c.table = table;
  c.validate();
  if (table != config_.table) allocate_table(table);
}

std::uint64_t GlHaBuffer::count_stored() {
  const GlStateGuard guard(bindings_);
  return clear_pass(false, nullptr);
}

FrameReport GlHaBuffer::frame(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls) {
  const GlStateGuard guard(bindings_);
  FrameReport report;
  report.index = frames_++;
  if (holds_frame_) {
    // The count the previous frame's clear pass left in the query buffer (the
    // GPU wrote it a frame ago: reading it does not stall), then this frame's
    // clear pass, whose count will be read next frame.
    if (pending_count_table_) {
      report.counted_stored = read_pending_count();
      report.counted_table = *pending_count_table_;
    }
    {
      const GlStateGuard clear_guard(bindings_);  // the gather gets the host's state back
      clear_pass(true, &report.clear, true);
    }
    pending_count_table_ = config_.table;
    report.cleared = true;
    holds_frame_ = false;
    if (options_.adaptive && report.counted_stored && report.counted_table == config_.table) {
      const Extent next = options_.policy.next(config_.table, config_.screen, *report.counted_stored);
      if (next != config_.table) {
        if (table_limit(next).empty()) {
          allocate_table(next);
          report.resized = true;
        } else {
          report.resize_limited = true;  // keep the largest table this context holds
        }
      }
    }
  }
  for (;;) {
    run_gather(gather, calls, report);
    if (options_.capture && report.captured > capture_capacity_) {
      // A gather is deterministic in what it rasterizes, so one regather suffices;
      // two would mean the host's gather is not repeatable.
      if (report.capture_regathers > 0)
        throw GlError("capture overflowed twice: the gather produced " + std::to_string(report.captured) +
                      " fragments after fitting a capture of " + std::to_string(capture_capacity_));
      grow_capture(report.captured);
      zero_buffer(gpu_->table);
      ++report.capture_regathers;
      continue;
    }
    if (deferred_overflow_ > 0) {
      // Calls cut short beyond the buffer lost their carried state: gather
      // again with room for all of them (contention varies between gathers,
      // so a few tries are allowed).
      if (report.deferred_regathers >= 8)
        throw GlError("insert calls cut short overflowed the deferred-call buffer 8 times (capacity " +
                      std::to_string(deferred_capacity_) + ")");
      grow_deferred(deferred_overflow_);
      zero_buffer(gpu_->table);
      ++report.deferred_regathers;
      continue;
    }
    if (report.cut_short > 0 && report.cut_short_retries < options_.cut_short_retries) {
      zero_buffer(gpu_->table);
      ++report.cut_short_retries;
      continue;
    }
    report.attempts.push_back({config_.table, report.counters});
    if (report.counters.failures() == 0 || report.attempts.size() >= options_.max_attempts) break;
    // Lossless mode: the same frame again. Failures of the table need a larger
    // one; calls cut short alone (contention or the driver, not load) retry
    // the same table.
    if (report.counters.failures() > report.cut_short) {
      const Extent grown = options_.policy.grown(config_.table);
      if (!table_limit(grown).empty()) {
        report.growth_limited = true;
        break;
      }
      allocate_table(grown);
    } else {
      zero_buffer(gpu_->table);
    }
  }
  report.table = config_.table;
  return report;
}

void GlHaBuffer::run_gather(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls,
                            FrameReport& report) {
  reset_frame_state();
  holds_frame_ = true;  // even if the gather throws halfway, the next frame clears what it inserted
  std::uint64_t unfinished = 0;
  {
    const GlStateGuard attempt_guard(bindings_);
    bind();
    PassClock clock(gpu_->gather_timer);
    gather();
    // Resolve, read-backs and the next clear see every insert.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    unfinished = resume_deferred(report);
    std::tie(report.gather.wall_ms, report.gather.gpu_ms) = clock.stop(options_.finish_timing);
  }
  std::tie(report.counters, report.slot_writes) = read_counters();
  if (options_.capture) report.captured = read_capture_count();
  check_gl_errors("the gather pass");
  report.cut_short = 0;
  if (deferred_overflow_ > 0) return;  // frame() grows the buffer and gathers again
  // Calls still cut short after the last round end as failed_iter.
  report.counters.fragments += unfinished;
  report.counters.failed_iter += unfinished;
  report.cut_short += unfinished;
  if (calls && !options_.capture_only) {
    const std::uint64_t made = calls();
    if (made < report.counters.fragments)
      throw GlError("the gather counted " + std::to_string(report.counters.fragments) + " insert calls, the host " +
                    std::to_string(made));
    // Calls a driver ended without an outcome or a deferral: nothing to resume.
    const std::uint64_t ended_by_driver = made - report.counters.fragments;
    report.counters.fragments += ended_by_driver;
    report.counters.failed_iter += ended_by_driver;
    report.cut_short += ended_by_driver;
  }
}

std::uint64_t GlHaBuffer::resume_deferred(FrameReport& report) {
  report.deferred = 0;
  report.resume_rounds = 0;
  int in = 0;
  std::uint64_t count = read_deferred_count(in);
  deferred_overflow_ = count > deferred_capacity_ ? count : 0;
  if (deferred_overflow_ > 0) return 0;
  // Every round ends at least one call per contended slot (a lock's holder
  // always completes its probe), so the rounds shrink the set; the bound
  // only guards against a driver that cuts every call at once. Our buffers
  // again at our points: the host's gather may have bound its own there.
  if (count > 0) bind();
  while (count > 0 && report.resume_rounds < options_.resume_rounds) {
    report.deferred += count;
    const int out = 1 - in;
    zero_range(gpu_->deferred[out], 0, kAppendHeaderBytes);
    glUseProgram(gpu_->resume->id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, bindings_.stream, gpu_->deferred[in]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, bindings_.deferred, gpu_->deferred[out]);
    gpu_->resume->set("ha_resume_count", static_cast<unsigned>(count));
    dispatch_grid(count, 64);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    ++report.resume_rounds;
    count = read_deferred_count(out);
    in = out;
  }
  return count;
}

PassTiming GlHaBuffer::resolve(glm::vec3 background, unsigned background_texture) {
  const GlStateGuard guard(bindings_);
  const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    GLint bound = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    throw GlError("resolve: the bound draw framebuffer " + std::to_string(bound) +
                  " is not complete (status 0x" + std::to_string(status) + "); bind one with a colour attachment");
  }
  bind();
  const auto [wall, gpu] = gpu_->resolve->run(config_.screen, background, background_texture, options_.finish_timing);
  check_gl_errors("the resolve pass");
  return {wall, gpu};
}

std::pair<Counters, std::uint64_t> GlHaBuffer::read_counters() const {
  const auto words = read_words(gpu_->counters, kCounterWords);
  std::uint64_t tally[HA_GPU_COUNTER_COUNT] = {};
  for (std::uint32_t stripe = 0; stripe < HA_COUNTER_STRIPES; ++stripe)
    for (std::uint32_t k = 0; k < HA_GPU_COUNTER_COUNT; ++k) tally[k] += words[stripe * HA_COUNTER_STRIDE + k];
  Counters c;
  c.add_tally(tally);
  return {c, tally[HA_COUNTER_SLOT_WRITES]};
}

std::uint64_t GlHaBuffer::read_capture_count() const {
  std::uint32_t count = 0;
  glGetNamedBufferSubData(gpu_->capture, 0, 4, &count);
  return count;
}

std::uint64_t GlHaBuffer::read_pending_count() const {
  std::uint64_t count = 0;
  glGetNamedBufferSubData(gpu_->count, 0, sizeof count, &count);
  return count;
}

std::uint64_t GlHaBuffer::read_deferred_count(int which) const {
  std::uint32_t count = 0;
  glGetNamedBufferSubData(gpu_->deferred[which], 0, 4, &count);
  return count;
}

std::vector<std::uint64_t> GlHaBuffer::read_table() const {
  const std::uint64_t slots = config_.table.area();
  std::vector<std::uint64_t> out(slots);
  if (config_.record_layout().word_bytes() == 8) {
    glGetNamedBufferSubData(gpu_->table, 0, static_cast<GLsizeiptr>(slots * 8), out.data());
  } else {
    const auto words = read_words(gpu_->table, slots);
    std::copy(words.begin(), words.end(), out.begin());
  }
  return out;
}

std::vector<std::uint32_t> GlHaBuffer::read_max_age() const { return read_words(gpu_->max_age, cells_); }

std::vector<Fragment> GlHaBuffer::read_capture() const {
  const std::uint64_t n = std::min(read_capture_count(), capture_capacity_);
  std::vector<Fragment> out(n);
  if (n > 0)
    glGetNamedBufferSubData(gpu_->capture, static_cast<GLintptr>(kAppendHeaderBytes),
                            static_cast<GLsizeiptr>(n * sizeof(Fragment)), out.data());
  return out;
}

std::uint64_t GlHaBuffer::memory_bytes() const {
  const std::uint64_t slots = config_.table.area();
  std::uint64_t bytes = slots * config_.record_layout().word_bytes() + std::uint64_t{cells_} * 4 +
                        offsets_.size() * sizeof(glm::uvec2) + kCounterWords * 4 + sizeof(GlParams) +
                        sizeof(std::uint64_t);
  if (mode_ == AtomicMode::Emulated64) bytes += slots * 4;
  if (capture_capacity_ > 0) bytes += kAppendHeaderBytes + capture_capacity_ * sizeof(Fragment);
  bytes += 2 * (kAppendHeaderBytes + deferred_capacity_ * kDeferredCallBytes);
  return bytes;
}

}  // namespace habuffer::gl
