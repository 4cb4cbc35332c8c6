#include "habuffer/gpu_tally.h"
#include "habuffer/gl/gl_frame_driver.h"

#include <cstddef>
#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "compute_grid.h"
#include "habuffer/gl/gl_technique.h"
#include "gl_state_guard.h"
#include "gpu_timer.h"
#include "late_readback.h"
#include "pixel_store.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/module_id.h"
#include "habuffer/gl/shader_program.h"
#include "light_params.h"
#include "resolve_pass.h"

namespace habuffer::gl {
namespace {

constexpr std::uint64_t kCounterWords = HABUFFER_COUNTER_WORDS;
constexpr std::uint64_t kAppendHeaderBytes = HABUFFER_APPEND_HEADER_WORDS * 4;
constexpr std::uint64_t kDeferredCallBytes = 40;  // std430 HaDeferred of ha_entry.glsl
static_assert(sizeof(Fragment) == 20 && offsetof(Fragment, coverage) == 16,
              "captured fragments are the std430 HaFragment (entry_common.glsl): change both together");

void zero_range(GLuint buffer, std::uint64_t offset, std::uint64_t bytes) {
  const NeutralUnpack unpack;  // the clear value is read through the host's unpack state
  const GLuint z = 0;
  glClearNamedBufferSubData(buffer, GL_R32UI, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &z);
}

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

std::unique_ptr<GlTechnique> checked(std::unique_ptr<GlTechnique> t) {
  if (!t) throw std::invalid_argument("the frame driver needs a technique");
  t->check_context("GlFrameDriver");  // the container's context, current here
  return t;
}

}  // namespace

struct GlFrameDriver::Gpu {
  GlStorage counters, capture, params;
  GlStorage deferred[2];  // ping-pong: the calls a round resumes, the calls it defers again
  std::unique_ptr<ResolvePass> resolve;
  std::unique_ptr<ResolvePass> resolve_per_sample;  // a multisampled buffer into a target of its samples
  std::unique_ptr<ShaderProgram> resume;
  GpuTimer gather_timer, reset_timer;
  LateReadback late;  // Readback::Deferred's ring of readbacks
};

std::string_view to_string(Readback readback) {
  return readback == Readback::Deferred ? "deferred" : "immediate";
}

GrowthNeed growth_need(const FrameReport& report) {
  return {report.nodes_requested, report.most_arrived, report.counters.records_needed()};
}

GlFrameDriver::GlFrameDriver(std::unique_ptr<GlTechnique> technique, const GlFrameOptions& options)
    : technique_(checked(std::move(technique))),
      options_(options),
      needs_call_count_(query_gl_info().software_rasterizer),
      gpu_(std::make_unique<Gpu>()) {
  options_.policy.validate();
  options_.module = options_.module.resolved(mode(), query_gl_info());
  needs_count_ = technique_->sized_automatically();
  module_id_ = module_fingerprint(module_text(ShaderStage::Fragment));
  if (!options_.readback) options_.readback = Readback::Immediate;
  const bool deferred = *options_.readback == Readback::Deferred;
  if (deferred && options_.finish_timing.value_or(false))
    throw std::invalid_argument("finish_timing waits for the GPU around every pass; a Deferred readback never waits: "
                                "leave it unset or false");
  if (!options_.finish_timing) options_.finish_timing = !deferred;
  late_rounds_ = options_.late_resume_rounds;
  if (!options_.max_attempts)
    options_.max_attempts = needs_count_ && !deferred ? GlFrameOptions::kAutomaticAttempts : 1u;
  if (*options_.max_attempts == 0) throw std::invalid_argument("at least one gather attempt is needed");
  made_attempts_ = *options_.max_attempts;
  if (deferred && *options_.max_attempts > 1)
    throw std::invalid_argument("max_attempts " + std::to_string(*options_.max_attempts) +
                                " regathers a frame that lost fragments, which needs that frame's count at once: "
                                "Readback::Immediate (a Deferred readback never waits)");
  if (deferred && options_.capture)
    throw std::invalid_argument("capture reads the frame's fragments back at once: Readback::Immediate");
  if (!(options_.attempt_budget_ms >= 0.0 && options_.attempt_budget_ms < 1e12))
    throw std::invalid_argument("attempt_budget_ms " + std::to_string(options_.attempt_budget_ms) +
                                " must be 0 (none) or a positive number of milliseconds");
  if (!(options_.growth_budget == 0.0 || (options_.growth_budget >= 1.0 && options_.growth_budget < 1e12)))
    throw std::invalid_argument("growth_budget " + std::to_string(options_.growth_budget) +
                                " must be 0 (none) or a factor of at least 1");
  if (options_.lock_spin_limit == 0) throw std::invalid_argument("the lock spin limit must be at least 1");
  if (options_.capture_only && !options_.capture) throw std::invalid_argument("capture_only needs capture");
  check_viewport_fits(screen());
  gpu_->counters = GlStorage(kCounterWords * 4);
  gpu_->params = GlStorage(sizeof(GlParams));
  gpu_->capture = GlStorage(kAppendHeaderBytes);
  if (options_.capture) grow_capture(std::max<std::uint64_t>(options_.capture_capacity, 1));
  if (technique_->defers_calls()) grow_deferred(std::max<std::uint64_t>(options_.deferred_capacity, 1));
  write_params();
  // Compile the passes now, so the first frame's timings measure the passes, not the compiler.
  const std::uint32_t samples = technique_->samples();
  gpu_->resolve = std::make_unique<ResolvePass>(
      resolve_fragment(technique_->technique(), mode(), bindings(), samples, SampleResolve::Pixel),
      to_string(technique_->technique()) + " resolve pass");
  if (samples > 1)
    gpu_->resolve_per_sample = std::make_unique<ResolvePass>(
        resolve_fragment(technique_->technique(), mode(), bindings(), samples, SampleResolve::Sample),
        to_string(technique_->technique()) + " per-sample resolve pass");
  if (technique_->defers_calls())
    gpu_->resume = std::make_unique<ShaderProgram>(
        ShaderProgram::compute(module_source(ShaderStage::Compute) + kResumeCompute, "resume compute shader"));
  check_gl_errors("creating the GPU frame buffers");
}

GlFrameDriver::~GlFrameDriver() = default;

std::string GlFrameDriver::module_text(ShaderStage stage, std::string_view header) const {
  const char* count_calls = needs_call_count_ ? "#define HABUFFER_COUNT_CALLS\n" : "";
  return technique_->module_source(stage, options_.module.defines() + light_module_defines(options_.light) +
                                              count_calls + std::string(header));
}

std::string GlFrameDriver::module_source(ShaderStage stage, std::string_view header) const {
  return module_text(stage, module_id_define(module_id_) + std::string(header));
}

void GlFrameDriver::check_refused_calls(const std::vector<std::uint32_t>& words) const {
  if (const std::uint32_t foreign = words[HABUFFER_COUNTER_FOREIGN]; foreign > 0)
    throw GlError(std::to_string(foreign) +
                  " insert calls came from a shader built from another driver's module_source() (another technique, "
                  "mode, binding points or variant): build the gather's shaders from this driver's");
  if (const std::uint32_t mismatched = words[HABUFFER_COUNTER_SAMPLES_MISMATCH]; mismatched > 0)
    throw GlError(std::to_string(mismatched) + " insert calls came from a framebuffer of " +
                  std::to_string(words[HABUFFER_COUNTER_SAMPLES_SEEN]) + " samples per pixel into a buffer of " +
                  std::to_string(technique_->samples()) + ": make the technique with that many samples "
                  "(BufferConfig::samples) so no pixel is resolved from one sample, or gather into a framebuffer of " +
                  std::to_string(technique_->samples()));
}

void GlFrameDriver::resize_screen(Extent screen) {
  technique_->check_context("resize_screen");
  const Extent before = this->screen();
  // Frames in flight were gathered on the old screen: read now (a wait, on
  // a resize only), handed over by the next frame().
  if (options_.readback == Readback::Deferred && screen != before)
    for (FrameReport& r : collect_late(true)) held_reports_.push_back(std::move(r));
  technique_->resize_screen(screen);  // strong guarantee: on a throw nothing changed
  write_params();                     // the block's screen for passes run before the next frame
  // An automatic container is counted again for the new screen (its depth
  // complexity need not scale with the area); counts of the old screen
  // (frames still in flight included) size nothing.
  if (screen != before) {
    if (technique_->sized_automatically()) needs_count_ = true;
    latest_count_.reset();
    sizing_floor_ = frames_;
  }
}

void GlFrameDriver::request_recount() {
  if (!technique_->sized_automatically())
    throw std::invalid_argument("request_recount: this " + to_string(technique_->technique()) +
                                " container was given its size (an automatic one is made without a table or pool)");
  needs_count_ = true;
}

std::size_t GlFrameDriver::frames_in_flight() const { return gpu_->late.pending(); }

std::vector<FrameReport> GlFrameDriver::finish_reports() {
  technique_->check_context("finish_reports");
  if (options_.readback != Readback::Deferred) return {};
  std::vector<FrameReport> out = std::exchange(held_reports_, {});
  for (FrameReport& r : collect_late(true)) out.push_back(std::move(r));
  return out;
}

void GlFrameDriver::note_count(const FrameReport& report) {
  if (report.index < sizing_floor_) return;
  if (latest_count_ && latest_count_->frame > report.index) return;
  const GrowthNeed need = growth_need(report);
  latest_count_ = SizingCount{report.index, need.records, need.nodes_requested};
}

bool GlFrameDriver::within_budget(const FrameReport& report, std::uint64_t start_capacity, double elapsed_ms) const {
  if (options_.attempt_budget_ms > 0.0 && elapsed_ms >= options_.attempt_budget_ms) return false;
  if (options_.growth_budget > 0.0) {
    // The capacity the policy grows to for this count (ResizePolicy::grown, its record form).
    const std::uint64_t next =
        options_.policy.grown(technique_->capacity(), growth_need(report).count_for(technique_->technique()));
    if (static_cast<double>(next) > options_.growth_budget * static_cast<double>(start_capacity)) return false;
  }
  return true;
}

bool GlFrameDriver::size_for(std::uint64_t fragments) {
  technique_->check_context("size_for");
  if (!technique_->sized_automatically())
    throw std::invalid_argument("size_for: this " + to_string(technique_->technique()) +
                                " container was given its size (an automatic one is made without a table or pool)");
  if (fragments > UINT32_MAX)
    throw GlError("a frame of " + std::to_string(fragments) +
                  " fragments overflows the GPU path's 32-bit counters: draw fewer fragments per frame");
  TechniqueConfig wanted;
  wanted.technique = technique_->technique();
  wanted.buffer.screen = screen();
  try {
    wanted = wanted.sized_for(options_.policy, fragments);
  } catch (const std::invalid_argument& e) {
    throw GlError(std::string("sizing for the counted fragments: ") + e.what());
  }
  const bool limited = technique_->fit_automatic_size(wanted);
  write_params();
  needs_count_ = false;
  // Sized for this count: counts of frames gathered before (the last one's,
  // frames still in flight) decide nothing.
  latest_count_.reset();
  sizing_floor_ = frames_;
  return limited;
}

void GlFrameDriver::set_light(const GlLightMapping& light) {
  if (!options_.light)
    throw std::invalid_argument("set_light: this driver was made without GlFrameOptions::light (its module has no "
                                "habuffer_insert_light)");
  (void)light_depth_map(light, GlWindowDepth{});  // refuses a mapping before anything changes
  options_.light = light;
  write_params();
}

void GlFrameDriver::write_params() const {
  GlParams p;
  p.habuffer_gather_phase = gather_phase_;
  p.habuffer_lock_spin_limit = options_.lock_spin_limit;
  p.habuffer_screen_size[0] = screen().x;
  p.habuffer_screen_size[1] = screen().y;
  p.habuffer_capture_capacity = static_cast<std::uint32_t>(capture_capacity_);
  p.habuffer_capture_only = options_.capture_only ? 1u : 0u;
  p.habuffer_deferred_capacity = static_cast<std::uint32_t>(deferred_capacity_);
  p.habuffer_depth_reversed = options_.depth == DepthConvention::Reversed ? 1u : 0u;
  p.habuffer_module_id = module_id_;
  p.habuffer_stop_at_failure = stop_at_failure_ ? 1u : 0u;
  write_light_params(options_.light, technique_->gather_depth(), p);
  technique_->write_params(p);
  glNamedBufferSubData(gpu_->params.id(), 0, sizeof p, &p);
}

void GlFrameDriver::grow_capture(std::uint64_t needed) {
  capture_capacity_ = grown_append_capacity(needed, capture_capacity_, sizeof(Fragment), "captured fragments");
  gpu_->capture = GlStorage();  // the old buffer goes first: the new one may need its memory
  gpu_->capture = GlStorage(kAppendHeaderBytes + capture_capacity_ * sizeof(Fragment));
}

void GlFrameDriver::grow_deferred(std::uint64_t needed) {
  deferred_capacity_ = grown_append_capacity(needed, deferred_capacity_, kDeferredCallBytes, "insert calls cut short");
  for (GlStorage& b : gpu_->deferred) {
    b = GlStorage();
    b = GlStorage(kAppendHeaderBytes + deferred_capacity_ * kDeferredCallBytes);
  }
}

namespace {

// The gather phase for one scope: back to inserting however the scope ends.
class PhaseScope {
 public:
  PhaseScope(std::uint32_t& phase, std::uint32_t value) : phase_(phase) { phase_ = value; }
  ~PhaseScope() { phase_ = HABUFFER_PHASE_INSERT; }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  std::uint32_t& phase_;
};

}  // namespace

void GlFrameDriver::run_phase_gather(std::uint32_t phase, const std::function<void()>& gather, FrameReport& report,
                                     const std::function<void()>& after) {
  const PhaseScope scope(gather_phase_, phase);
  write_params();
  {
    const GlStateGuard guard(bindings());
    bind();
    run_passes(GlPassStage::Gather, report);
    gather();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    finish_gather_passes();
    if (after) {
      bind();  // the host's gather may have bound its own buffers at our points
      after();
    }
  }
  write_params();  // the inserting phase's block for what follows
}

void GlFrameDriver::count_and_size(const std::function<void()>& gather, FrameReport& report) {
  const auto t0 = std::chrono::steady_clock::now();
  gpu_->counters.zero();
  run_phase_gather(HABUFFER_PHASE_COUNT, gather, report);
  const std::vector<std::uint32_t> words = gpu_->counters.read_words(kCounterWords);
  check_gl_errors("the counting gather");
  check_refused_calls(words);
  const std::uint64_t fragments = stripe_tally(words)[HABUFFER_COUNTER_COUNTED];
  report.counted_fragments = fragments;
  report.count_limited = size_for(fragments);
  sizing_floor_ = report.index;  // this frame, sized by its own count, sizes the next
  report.count.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void GlFrameDriver::reset_frame_state() const {
  gpu_->counters.zero();
  zero_range(gpu_->capture.id(), 0, kAppendHeaderBytes);
  if (gpu_->deferred[0]) zero_range(gpu_->deferred[0].id(), 0, kAppendHeaderBytes);
}

void GlFrameDriver::bind() const {
  technique_->check_context("bind");
  // bind_at leaves the generic bindings the host's, so a host that updates
  // "its" GL_UNIFORM_BUFFER or GL_SHADER_STORAGE_BUFFER inside the gather
  // writes its own buffer.
  technique_->bind();
  const GlBindings& b = bindings();
  gpu_->counters.bind_storage(b.counters);
  gpu_->capture.bind_storage(b.capture);
  gpu_->deferred[0].bind_storage(b.deferred);
  bind_at(GL_UNIFORM_BUFFER, b.params, gpu_->params.id());
}

namespace {

// Throws GlError when the depth test enabled now keeps the other
// convention's nearest fragments: habuffer_insert_here would sort every list
// back to front, silently.
void check_depth_convention(DepthConvention convention) {
  if (!glIsEnabled(GL_DEPTH_TEST)) return;
  GLint func = 0;
  glGetIntegerv(GL_DEPTH_FUNC, &func);
  const bool greater = func == GL_GREATER || func == GL_GEQUAL, less = func == GL_LESS || func == GL_LEQUAL;
  if (convention == DepthConvention::Standard && greater)
    throw GlError(std::string("the depth test is ") + (func == GL_GREATER ? "GL_GREATER" : "GL_GEQUAL") +
                  " (reversed-Z) but GlFrameOptions::depth is Standard: set DepthConvention::Reversed");
  if (convention == DepthConvention::Reversed && less)
    throw GlError(std::string("the depth test is ") + (func == GL_LESS ? "GL_LESS" : "GL_LEQUAL") +
                  " but GlFrameOptions::depth is Reversed: set DepthConvention::Standard");
}

}  // namespace

FrameReport GlFrameDriver::frame(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls,
                                const GrowthCheck& may_grow) {
  technique_->check_context("frame");
  check_depth_convention(options_.depth);
  if (technique_->samples() > 1 && glIsEnabled(GL_SAMPLE_SHADING))
    throw GlError("frame: sample shading is on: every sample would insert a record of its own; switch it off for the "
                  "gather (each fragment's coverage mask names its samples)");
  technique_->record_gather_depth(gather_depth_now(options_));  // what this frame's depths will be
  const GlStateGuard guard(bindings());
  const bool deferred = options_.readback == Readback::Deferred;
  FrameReport report;
  // Earlier frames whose fences signalled: read without a wait, their count
  // sizes this frame.
  if (deferred) {
    report.completed = std::exchange(held_reports_, {});
    for (FrameReport& r : collect_late(false)) report.completed.push_back(std::move(r));
  }
  report.index = frames_++;
  if (has_passes(GlPassStage::FrameStart)) {
    const GlStateGuard begin_guard(bindings());  // the gather gets the host's state back
    write_params();
    bind();
    run_passes(GlPassStage::FrameStart, report);
  }
  if (needs_count_) count_and_size(gather, report);  // an automatic container's first frame on this screen
  report.sized_by = std::exchange(latest_count_, std::nullopt);
  technique_->begin_frame(report, options_);         // sizing only, no GL state touched
  if (deferred) {
    run_deferred_gather(gather, report);
    return report;
  }
  const auto frame_t0 = std::chrono::steady_clock::now();
  const std::uint64_t start_capacity = technique_->capacity();
  std::uint64_t sized_for = 0;  // the count the next attempt is sized by
  auto attempt_t0 = frame_t0;
  const auto ms_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  const std::uint32_t allowed = std::max<std::uint32_t>(*options_.max_attempts, technique_->grows_at_once() ? 2 : 1);
  for (;;) {
    // A lossless attempt that a regather may follow stops inserting at its
    // first failure: it only needs to count (the HA-buffer's table, whose
    // overfull probes are the costly ones).
    stop_at_failure_ = uses_table(technique_->technique()) && !options_.capture_only &&
                       report.attempts.size() + 1 < allowed && !report.growth_refused;
    run_gather(gather, calls, report);
    if (options_.capture && report.captured > capture_capacity_) {
      // A gather is deterministic in what it rasterizes, so one regather suffices;
      // two would mean the host's gather is not repeatable.
      if (report.capture_regathers > 0)
        throw GlError("capture overflowed twice: the gather produced " + std::to_string(report.captured) +
                      " fragments after fitting a capture of " + std::to_string(capture_capacity_));
      grow_capture(report.captured);
      technique_->reset();
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
      technique_->reset();
      ++report.deferred_regathers;
      continue;
    }
    if (report.cut_short > 0 && report.cut_short_retries < options_.cut_short_retries) {
      technique_->reset();
      ++report.cut_short_retries;
      continue;
    }
    report.attempts.push_back({report.table, report.counters, technique_->capacity(), sized_for, ms_since(attempt_t0)});
    attempt_t0 = std::chrono::steady_clock::now();
    if (report.counters.failures() == 0 || report.attempts.size() >= allowed || report.growth_refused) break;
    // Failures that are all calls cut short (contention or the driver, not
    // the technique's size): the same buffers, emptied, again.
    if (report.counters.failures() <= report.cut_short) {
      technique_->reset();
      continue;
    }
    if (!within_budget(report, start_capacity, ms_since(frame_t0))) {
      report.budget_stopped = true;
      break;
    }
    if (may_grow && !may_grow(report)) {
      // No growth: the frame keeps this container. A gather that stopped
      // inserting at its first failure runs once more, inserting every call.
      report.growth_refused = true;
      if (!stop_at_failure_) break;
      technique_->reset();
      continue;
    }
    // Lossless mode: the same frame again, sized for what this gather counted.
    sized_for = growth_need(report).count_for(technique_->technique());
    if (!technique_->grow(report, options_)) {
      report.growth_limited = true;
      break;
    }
  }
  stop_at_failure_ = false;
  report.capacity = technique_->capacity();
  note_count(report);
  return report;
}

void GlFrameDriver::run_deferred_gather(const std::function<void()>& gather, FrameReport& report) {
  const auto t0 = std::chrono::steady_clock::now();
  LateReadback& late = gpu_->late;
  const std::uint32_t rounds = technique_->defers_calls() ? late_rounds_ : 0;
  LateReadback::Slot& slot = late.begin(kCounterWords + 1 + rounds);
  try {
    late.mark(LateReadback::FrameBegin);
    reset_frame_state();
    technique_->before_gather();
    if (has_passes(GlPassStage::Fill)) (void)run_fill(gather, report);
    write_params();
    {
      const GlStateGuard attempt_guard(bindings());
      bind();
      run_passes(GlPassStage::Gather, report);
      late.mark(LateReadback::GatherBegin);
      gather();
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
      finish_gather_passes();
      bind();  // the host's gather may have bound its own buffers at our points
      if (technique_->defers_calls()) {
        // Resume rounds dispatched for the buffer's capacity, each reading
        // its calls' count on the GPU (resume.comp.glsl), each count copied
        // for the late report: the calls deferred, those lost to an
        // overflow, those still cut short after the last round.
        late.copy(gpu_->deferred[0].id(), 0, kCounterWords, 4);
        int in = 0;
        for (std::uint32_t r = 0; r < rounds; ++r) {
          in = dispatch_resume_round(in, deferred_capacity_);  // the round reads its count on the GPU
          late.copy(gpu_->deferred[in].id(), 0, kCounterWords + 1 + r, 4);
        }
        slot.frame.rounds = rounds;
      }
      late.mark(LateReadback::GatherEnd);
      sorted_ = !options_.capture_only && has_passes(GlPassStage::Sort);
      if (sorted_) {
        bind();
        run_passes(GlPassStage::Sort, report);
      }
    }
    late.mark(LateReadback::FrameEnd);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    late.copy(gpu_->counters.id(), 0, 0, kCounterWords * 4);
    check_gl_errors("the gather pass");
    report.complete = false;
    report.capacity = technique_->capacity();
    report.table = technique_->table_extent();
    LateFrame& frame = slot.frame;
    frame.report = report;
    frame.report.completed.clear();
    frame.capacity = report.capacity;
    frame.deferred_capacity = deferred_capacity_;
    frame.sorted = sorted_;
    frame.submit_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    report.gather.wall_ms = frame.submit_ms;
    late.end();
  } catch (...) {
    late.abandon();
    throw;
  }
}

std::vector<FrameReport> GlFrameDriver::collect_late(bool wait) {
  std::vector<FrameReport> out;
  for (LateReadback::Done& d : gpu_->late.collect(wait)) {
    FrameReport r = std::move(d.frame.report);
    r.complete = true;
    sorted_ = d.frame.sorted;
    (void)read_counters_from(d.words, r);
    // The resume rounds' counts: calls beyond a buffer's capacity lost their
    // carried state, calls left after the last round stayed cut short; both
    // end as failed_iter (SPEC invariant 1), and the buffer grows for later frames.
    std::uint64_t unfinished = 0;
    if (technique_->defers_calls()) {
      const std::uint64_t cap = d.frame.deferred_capacity;
      std::uint64_t most = 0;
      for (std::uint32_t k = 0; k <= d.frame.rounds; ++k) {
        const std::uint64_t h = d.words[kCounterWords + k];
        most = std::max(most, h);
        if (h > cap) unfinished += h - cap;
        if (k < d.frame.rounds) r.deferred += std::min(h, cap);
        if (k > 0 && h > 0) r.resume_rounds = k;
      }
      const std::uint64_t left = std::min<std::uint64_t>(d.words[kCounterWords + d.frame.rounds], cap);
      unfinished += left;
      if (most > deferred_capacity_) grow_deferred(most);
      // The rounds later frames dispatch: twice what recent frames needed
      // (all they had, when calls were left), decaying by one a frame, at
      // least one, at most late_resume_rounds: an empty dispatch is nearly
      // free on a GPU but not on llvmpipe.
      const std::uint32_t wanted = 2 * (left > 0 ? d.frame.rounds : r.resume_rounds);
      const std::uint32_t decayed = late_rounds_ > 1 ? late_rounds_ - 1 : 1;
      late_rounds_ = std::min(options_.late_resume_rounds, std::max(wanted, decayed));
    }
    r.counters.fragments += unfinished;
    r.counters.failed_iter += unfinished;
    r.cut_short = unfinished;
    if (needs_call_count_ && !options_.capture_only) count_own_calls(d.words, r);
    const Extent table = r.table;
    technique_->gathered(d.words, r);
    r.table = table;  // the table it was gathered into, not the current one
    r.capacity = d.frame.capacity;
    r.reset = {0.0, d.gpu_ms[0]};
    r.gather = {d.frame.submit_ms, d.gpu_ms[1]};
    r.sort = {0.0, d.gpu_ms[2]};
    r.attempts = {BuildAttempt{r.table, r.counters, r.capacity, 0, d.frame.submit_ms}};
    note_count(r);
    out.push_back(std::move(r));
  }
  return out;
}

bool GlFrameDriver::has_passes(GlPassStage stage) const {
  const auto& passes = technique_->passes();
  return std::any_of(passes.begin(), passes.end(), [&](const GlPass& p) { return p.stage == stage; });
}

void GlFrameDriver::run_passes(GlPassStage stage, FrameReport& report) const {
  GlPassContext context{report, options_};
  for (const GlPass& p : technique_->passes()) {
    if (p.stage != stage) continue;
    p.run(context);
    // The Gather stage's GL calls are state for the host's draws: checked with the gather.
    if (stage != GlPassStage::Gather) check_gl_errors(p.name.c_str());
  }
}

void GlFrameDriver::finish_gather_passes() const {
  for (const GlPass& p : technique_->passes())
    if (p.stage == GlPassStage::Gather && p.finish) p.finish();
}

double GlFrameDriver::run_fill(const std::function<void()>& gather, FrameReport& report) {
  // A pass of the host's scene that inserts nothing (the k-buffer's
  // occupancy fill), then the technique's own pass over what it gathered.
  const auto t0 = std::chrono::steady_clock::now();
  run_phase_gather(HABUFFER_PHASE_FILL, gather, report, [&] { run_passes(GlPassStage::Fill, report); });
  if (clock_mode(options_) == ClockMode::Finish) glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void GlFrameDriver::run_gather(const std::function<void()>& gather, const std::function<std::uint64_t()>& calls,
                               FrameReport& report) {
  {
    PassClock clock(gpu_->reset_timer, clock_mode(options_));
    reset_frame_state();
    technique_->before_gather();
    std::tie(report.reset.wall_ms, report.reset.gpu_ms) = clock.stop();
  }
  const double fill_ms = has_passes(GlPassStage::Fill) ? run_fill(gather, report) : 0.0;
  write_params();
  std::uint64_t unfinished = 0;
  {
    const GlStateGuard attempt_guard(bindings());
    bind();
    run_passes(GlPassStage::Gather, report);
    {
      PassClock clock(gpu_->gather_timer, clock_mode(options_));
      gather();
      // Resolve, read-backs and the next clear see every insert.
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
      finish_gather_passes();
      std::tie(report.gather.wall_ms, report.gather.gpu_ms) = clock.stop();
    }
    // The deferred count is read after the clock (a read-back inside it
    // would time a stall, not the gather); resume rounds, if any, add their own span.
    unfinished = resume_deferred(report);
    report.gather.wall_ms += fill_ms;
    // A gather frame() will repeat (a buffer overflowed) is not worth sorting.
    if (options_.capture) report.captured = read_capture_count();
    const bool repeated = deferred_overflow_ > 0 || (options_.capture && report.captured > capture_capacity_);
    sorted_ = !repeated && !options_.capture_only && has_passes(GlPassStage::Sort);
    if (sorted_) {
      bind();  // the host's gather may have bound its own buffers at our points
      run_passes(GlPassStage::Sort, report);
    }
  }
  const std::vector<std::uint32_t> counter_words = read_counters(report);
  check_gl_errors("the gather pass");
  report.cut_short = 0;
  if (deferred_overflow_ > 0) return;  // frame() grows the buffer and gathers again
  // Calls still cut short after the last round end as failed_iter.
  report.counters.fragments += unfinished;
  report.counters.failed_iter += unfinished;
  report.cut_short += unfinished;
  if (needs_call_count_ && !options_.capture_only) {
    if (calls)
      count_ended_by_driver(calls(), report);
    else
      count_own_calls(counter_words, report);
  }
  technique_->gathered(counter_words, report);
}

void GlFrameDriver::count_own_calls(std::span<const std::uint32_t> words, FrameReport& report) const {
  // The module's own count (HABUFFER_COUNT_CALLS) covers the shaders built
  // from module_source(); a gather from the installed GLSL files counts no
  // calls, so a count below the outcomes (never possible otherwise: a call
  // is counted before its outcome) means there is nothing to reconcile.
  const std::uint64_t made = std::uint64_t{words[HABUFFER_COUNTER_CALLS]} + report.off_screen;
  if (made >= report.counters.fragments) count_ended_by_driver(made, report);
}

void GlFrameDriver::count_ended_by_driver(std::uint64_t made, FrameReport& report) const {
  if (made < report.counters.fragments)
    throw GlError("the gather counted " + std::to_string(report.counters.fragments) + " insert calls, " +
                  std::to_string(made) + " were made");
  // Calls a driver ended without an outcome or a deferral: nothing to resume.
  const std::uint64_t ended_by_driver = made - report.counters.fragments;
  report.counters.fragments += ended_by_driver;
  report.counters.failed_iter += ended_by_driver;
  report.cut_short += ended_by_driver;
}

int GlFrameDriver::dispatch_resume_round(int in, std::uint64_t count) {
  const int out = 1 - in;
  zero_range(gpu_->deferred[out].id(), 0, kAppendHeaderBytes);
  glUseProgram(gpu_->resume->id());
  gpu_->deferred[in].bind_storage(bindings().stream);
  gpu_->deferred[out].bind_storage(bindings().deferred);
  gpu_->resume->set("ha_resume_count", static_cast<unsigned>(count));
  dispatch_grid(count, 64);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  return out;
}

std::uint64_t GlFrameDriver::resume_deferred(FrameReport& report) {
  report.deferred = 0;
  report.resume_rounds = 0;
  deferred_overflow_ = 0;
  if (!technique_->defers_calls()) return 0;
  int in = 0;
  std::uint64_t count = read_deferred_count(in);
  deferred_overflow_ = count > deferred_capacity_ ? count : 0;
  if (deferred_overflow_ > 0) return 0;
  // Every round ends at least one call per contended slot (a lock's holder
  // always completes its probe), so the rounds shrink the set; the bound
  // only guards against a driver that cuts every call at once. Our buffers
  // again at our points: the host's gather may have bound its own there.
  if (count == 0) return 0;
  bind();
  // The rounds' own span (each count read waits for its round: part of it).
  PassClock clock(gpu_->gather_timer, clock_mode(options_));
  while (count > 0 && report.resume_rounds < options_.resume_rounds) {
    report.deferred += count;
    const int out = dispatch_resume_round(in, count);
    ++report.resume_rounds;
    count = read_deferred_count(out);
    in = out;
  }
  const auto [wall_ms, gpu_ms] = clock.stop();
  report.gather.wall_ms += wall_ms;
  report.gather.gpu_ms += gpu_ms;
  return count;
}

std::vector<std::uint32_t> GlFrameDriver::read_counters(FrameReport& report) const {
  std::vector<std::uint32_t> words = gpu_->counters.read_words(kCounterWords);
  return read_counters_from(std::move(words), report);
}

std::vector<std::uint32_t> GlFrameDriver::read_counters_from(std::vector<std::uint32_t> words,
                                                            FrameReport& report) const {
  check_refused_calls(words);
  const std::array<std::uint64_t, HABUFFER_GPU_COUNTER_COUNT> sums = stripe_tally(words);
  const std::uint64_t* tally = sums.data();
  const std::uint64_t pixels = screen().area();
  if (sorted_ && tally[HABUFFER_COUNTER_SORT_DONE] != pixels)
    throw GlError("the driver ended " + std::to_string(pixels - tally[HABUFFER_COUNTER_SORT_DONE]) + " of " +
                  std::to_string(pixels) +
                  " per-pixel sorts early (its loop budget): the lists are too long for this driver's sort pass");
  Counters c;
  c.add_tally(tally);
  c.merge_duplicates(tally[HABUFFER_COUNTER_MERGED]);
  report.counters = c;
  report.slot_writes.reset();
  if (options_.module.count_writes) report.slot_writes = tally[HABUFFER_COUNTER_SLOT_WRITES];
  report.off_screen = tally[HABUFFER_COUNTER_OFF_SCREEN];
  // Calls a lossless attempt counted after its first failure without
  // inserting them (habuffer_stop_at_failure): failed_iter of that attempt.
  report.skipped = stop_at_failure_ ? tally[HABUFFER_COUNTER_COUNTED] : 0;
  report.counters.fragments += report.skipped;
  report.counters.failed_iter += report.skipped;
  return words;  // the technique reads its own words (GlTechnique::gathered)
}

PassTiming GlFrameDriver::resolve(glm::vec3 background, unsigned background_texture) {
  return run_resolve(background, background_texture, false);
}

PassTiming GlFrameDriver::resolve_over() { return run_resolve(glm::vec3(0.0f), 0, true); }

PassTiming GlFrameDriver::run_resolve(glm::vec3 background, unsigned background_texture, bool over) {
  technique_->check_context(over ? "resolve_over" : "resolve");
  const GlStateGuard guard(bindings());
  const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    GLint bound = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    throw GlError("resolve: the bound draw framebuffer " + std::to_string(bound) +
                  " is not complete (status 0x" + std::to_string(status) + "); bind one with a colour attachment");
  }
  // A multisampled buffer resolves per sample into a target of its samples,
  // per pixel into a single-sampled one; a buffer of one sample resolves
  // into any target (each sample gets its pixel's colour).
  GLint target_samples = 0;
  glGetIntegerv(GL_SAMPLES, &target_samples);
  const std::uint32_t samples = technique_->samples(), target = std::max(1, target_samples);
  if (samples > 1 && target != 1 && target != samples)
    throw GlError(std::string(over ? "resolve_over" : "resolve") + ": the bound draw framebuffer has " +
                  std::to_string(target) + " samples per pixel and the buffer " + std::to_string(samples) +
                  ": resolve into a framebuffer of " + std::to_string(samples) + " (per sample) or 1 (per pixel)");
  ResolvePass& pass = samples > 1 && target == samples ? *gpu_->resolve_per_sample : *gpu_->resolve;
  bind();
  const auto [wall, gpu] = over ? pass.run_over(screen(), clock_mode(options_))
                                : pass.run(screen(), background, background_texture, clock_mode(options_));
  check_gl_errors("the resolve pass");
  return {wall, gpu};
}

std::uint64_t GlFrameDriver::read_capture_count() const {
  std::uint32_t count = 0;
  glGetNamedBufferSubData(gpu_->capture.id(), 0, 4, &count);
  return count;
}

std::uint64_t GlFrameDriver::read_deferred_count(int which) const {
  std::uint32_t count = 0;
  glGetNamedBufferSubData(gpu_->deferred[which].id(), 0, 4, &count);
  return count;
}

std::vector<Fragment> GlFrameDriver::read_capture() const {
  technique_->check_context("read_capture");
  const std::uint64_t n = std::min(read_capture_count(), capture_capacity_);
  std::vector<Fragment> out(n);
  if (n > 0)
    glGetNamedBufferSubData(gpu_->capture.id(), static_cast<GLintptr>(kAppendHeaderBytes),
                            static_cast<GLsizeiptr>(n * sizeof(Fragment)), out.data());
  return out;
}

std::uint64_t GlFrameDriver::capture_bytes() const { return gpu_->capture.bytes(); }

std::uint64_t GlFrameDriver::memory_bytes() const {
  return technique_->memory_bytes() + gpu_->late.bytes() +
         bytes_of(gpu_->counters, gpu_->params, gpu_->capture, gpu_->deferred[0], gpu_->deferred[1]);
}

}  // namespace habuffer::gl
