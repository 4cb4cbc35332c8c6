#include "habuffer/vk/vulkan_build.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "habuffer/attempt_need.h"
#include "habuffer/gpu_tally.h"
#include "habuffer/shared/ha_constants.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_params.h"
#include "habuffer/vk/compute_pipeline.h"
#include "habuffer/vk/frame_buffers.h"
#include "habuffer/vk/spirv_compiler.h"
#include "habuffer/vk/vulkan_buffer.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_glsl.h"
#include "habuffer/vk/vulkan_registry.h"

namespace habuffer::vk {
namespace {

constexpr std::uint64_t kCounterWords = HABUFFER_COUNTER_WORDS;
constexpr std::uint64_t kAppendHeaderBytes = HABUFFER_APPEND_HEADER_WORDS * 4;
constexpr std::uint64_t kDeferredCallBytes = 40;  // std430 HaDeferred of ha_entry.glsl (hash_kernel.h checks it)
constexpr std::uint32_t kMaxResumeRounds = 1u << 16;
constexpr std::uint32_t kMaxOverflowRegathers = 8;
static_assert(sizeof(Fragment) == 20, "the stream is the std430 HaFragment of entry_common.glsl");

// The pipelines and frame buffers of one build: the stream in chunks of at
// most one storage binding, the counters, the deferred calls' ping-pong.
class StreamGather {
 public:
  // The pipelines (compiled here) and the frame's own buffers.
  StreamGather(const VulkanContext& context, Technique technique, AtomicMode mode)
      : context_(context),
        params_(context, sizeof(ParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
        counters_(context, kCounterWords * 4),
        capture_(context, kAppendHeaderBytes + sizeof(Fragment)),
        insert_(make_pipeline(vulkan_insert_stream_compute(technique, mode, frame_variant_defines(mode, context.info())),
                              to_string(technique) + " insert (Vulkan, " + to_string(mode) + ")")) {
    if (!descriptor(technique).sorted_on_insert) {
      const std::string name = to_string(technique) + " sort (Vulkan, " + to_string(mode) + ")";
      sort_ = std::make_unique<ComputePipeline>(
          context, compute_spirv(vulkan_sort_compute(technique, mode, frame_variant_defines(mode, context.info())), name),
          name);
    }
    // Until a technique that defers calls comes (prepare): a header whose
    // count a call the driver cuts short may raise (capacity 0: nothing
    // stored), and which is counted as ended by the driver.
    deferred_[0] = VulkanBuffer(context, kAppendHeaderBytes);
  }

  // Before `t`'s first gather, out of the timed span: where its calls may be
  // cut short and deferred (emulated64's locks), the resume pass and the
  // deferred calls' buffers.
  void prepare(const VulkanTechnique& t) {
    if (t.fills_before_insert() && !fill_) {
      const std::string name =
          to_string(t.config().technique) + " fill pass (Vulkan, " + to_string(t.mode()) + ")";
      fill_ = std::make_unique<ComputePipeline>(
          context_, compute_spirv(t.fill_pass_compute(frame_variant_defines(t.mode(), context_.info())), name), name);
    }
    if (!t.defers_calls() || resume_) return;
    const TechniqueConfig& c = t.config();
    const std::string name = to_string(c.technique) + " resume (Vulkan, " + to_string(t.mode()) + ")";
    resume_ = std::make_unique<ComputePipeline>(
        context_,
        compute_spirv(vulkan_resume_compute(c.technique, t.mode(), frame_variant_defines(t.mode(), context_.info())), name),
        name);
    grow_deferred(1u << 12);
  }

  // The stream, in chunks of at most one storage binding (kept for every attempt).
  void upload(std::span<const Fragment> fragments) {
    chunks_.clear();
    stream_size_ = fragments.size();
    const std::uint64_t per_chunk =
        std::max<std::uint64_t>(1, std::min<std::uint64_t>(context_.info().max_storage_range / sizeof(Fragment),
                                                           std::uint64_t{1} << 26));
    for (std::uint64_t first = 0; first < fragments.size() || first == 0;) {
      const std::uint64_t n = std::min<std::uint64_t>(per_chunk, fragments.size() - first);
      Chunk c{VulkanBuffer(context_, std::max<std::uint64_t>(n, 1) * sizeof(Fragment)), n};
      c.buffer.upload(fragments.data() + first, n * sizeof(Fragment));
      chunks_.push_back(std::move(c));
      first += n;
      if (fragments.empty()) break;
    }
  }

  // One gather of the whole stream into `t` (cleared first), sorted where
  // the technique sorts after it: the attempt's counters.
  Counters gather(VulkanTechnique& t, VulkanBuildInfo& info) {
    // A technique that fills first (the k-buffer's occupancy map) gathers
    // the stream twice, its own passes between: as the OpenGL frame does.
    const bool fills = t.fills_before_insert();
    for (std::uint32_t regather = 0;; ++regather) {
      for (const std::uint32_t phase : {HABUFFER_PHASE_FILL, HABUFFER_PHASE_INSERT}) {
        if (phase == HABUFFER_PHASE_FILL && !fills) continue;
        write_params(t, phase);
        insert_.begin_recording();
        const bool first = phase == HABUFFER_PHASE_FILL || !fills;
        context_.submit_and_wait(
            [&](VkCommandBuffer cmd) {
              if (first) {
                t.record_clear(cmd);
                counters_.record_zero(cmd);
                capture_.record_zero(cmd);
                record_full_barrier(cmd);
              }
              deferred_[0].record_zero(cmd);  // the insert gather's calls cut short, none yet
              record_full_barrier(cmd);
              for (const Chunk& c : chunks_) {
                insert_.record(cmd, bindings(t, c.buffer, deferred_[0]), static_cast<std::uint32_t>(c.count),
                               c.count);
                record_full_barrier(cmd);  // chunks run in stream order: the next sees every write of this one
              }
              if (phase == HABUFFER_PHASE_FILL) {
                fill_->begin_recording();  // the submission that used its last set has ended
                fill_->record_screen(cmd, bindings(t, chunks_.front().buffer, deferred_[0]), t.config().buffer.screen);
                record_full_barrier(cmd);
              }
            },
            phase == HABUFFER_PHASE_FILL ? "the Vulkan fill gather" : "the Vulkan gather");
      }
      if (!t.defers_calls() || resume_all(t, info)) break;
      // More calls were cut short than the deferred buffer holds: grown, and gathered again.
      if (regather + 1 >= kMaxOverflowRegathers)
        throw VulkanError("insert calls cut short overflowed the deferred-call buffer " +
                          std::to_string(kMaxOverflowRegathers) + " times (capacity " + std::to_string(capacity_) + ")");
    }
    if (t.sorts_after_gather()) sort(t);
    const std::vector<std::uint32_t> words = counters_.read<std::uint32_t>(kCounterWords);
    Counters c = counters_from_words(words);
    const std::uint64_t sorted = stripe_tally(words)[HABUFFER_COUNTER_SORT_DONE];
    if (t.sorts_after_gather() && sorted != t.config().buffer.screen.area())
      throw VulkanError("the driver ended " + std::to_string(t.config().buffer.screen.area() - sorted) +
                        " per-pixel sorts early (its loop budget): the lists are too long for this driver's sort pass");
    t.gathered(words);
    // Calls the driver ended without an outcome (a loop budget): counted as
    // failed at the iteration limit, as the OpenGL path does.
    if (c.fragments > stream_size_)
      throw VulkanError("the gather counted " + std::to_string(c.fragments) + " insert calls, " +
                        std::to_string(stream_size_) + " were made");
    const std::uint64_t ended = stream_size_ - c.fragments;
    c.fragments += ended;
    c.failed_iter += ended;
    info.ended_by_driver += ended;
    return c;
  }

  // `t`'s image over `backgrounds` (one per pixel): the resolve pass, in
  // place in an image buffer bound at the stream's point.
  // Compiles the resolve pass for `t`'s screen (once per sample count).
  void prepare_resolve(const VulkanTechnique& t) {
    const TechniqueConfig& c = t.config();
    if (resolve_ && resolve_samples_ == c.buffer.samples) return;
    const std::string name = to_string(c.technique) + " resolve (Vulkan, " + to_string(t.mode()) + ")";
    resolve_ = std::make_unique<ComputePipeline>(
        context_,
        compute_spirv(
            vulkan_resolve_compute(c.technique, t.mode(), c.buffer.samples, frame_variant_defines(t.mode(), context_.info())),
            name),
        name);
    resolve_samples_ = c.buffer.samples;
  }

  std::vector<glm::vec4> resolve(const VulkanTechnique& t, std::span<const glm::vec3> backgrounds) {
    const TechniqueConfig& c = t.config();
    prepare_resolve(t);
    if (backgrounds.size() * sizeof(glm::vec4) > context_.info().max_storage_range)
      throw VulkanError("the resolve's image of screen " + c.buffer.screen.str() + " needs " +
                        std::to_string(backgrounds.size() * sizeof(glm::vec4)) + " bytes, beyond one storage binding of " +
                        context_.info().name);
    std::vector<glm::vec4> image(backgrounds.size());
    for (std::size_t i = 0; i < backgrounds.size(); ++i) image[i] = glm::vec4(backgrounds[i], 0.0f);
    VulkanBuffer target(context_, std::max<std::uint64_t>(image.size(), 1) * sizeof(glm::vec4));
    target.upload(image.data(), image.size() * sizeof(glm::vec4));
    write_params(t, HABUFFER_PHASE_INSERT);
    resolve_->begin_recording();
    context_.submit_and_wait(
        [&](VkCommandBuffer cmd) {
          resolve_->record_screen(cmd, bindings(t, target, deferred_[0]), c.buffer.screen);
          record_full_barrier(cmd);
        },
        "the Vulkan resolve pass");
    return target.read<glm::vec4>(image.size());
  }

 private:
  struct Chunk {
    VulkanBuffer buffer;
    std::uint64_t count = 0;
  };

  ComputePipeline make_pipeline(const std::string& source, const std::string& name) const {
    return ComputePipeline(context_, compute_spirv(source, name), name);
  }
  static std::vector<std::uint32_t> compute_spirv(const std::string& source, const std::string& name) {
    return compile_to_spirv(source, SpirvStage::Compute, name);
  }

  void write_params(const VulkanTechnique& t, std::uint32_t gather_phase) {
    ParamBlock p = frame_params(t, gather_phase);
    p.habuffer_deferred_capacity = static_cast<std::uint32_t>(capacity_);
    params_.upload(&p, sizeof p);
  }

  std::vector<BoundBuffer> bindings(const VulkanTechnique& t, const VulkanBuffer& stream,
                                    const VulkanBuffer& deferred) const {
    return frame_bindings(t, FrameBuffers{&params_, &counters_, &capture_, &stream, &deferred});
  }

  // The deferred calls' buffers, both of `needed` calls at least (doubling).
  // The capacity changes only once both buffers hold it (a throw leaves the old ones).
  void grow_deferred(std::uint64_t needed) {
    const std::uint64_t capacity = std::min<std::uint64_t>(std::max(needed, capacity_ * 2), UINT32_MAX);
    const std::uint64_t bytes = kAppendHeaderBytes + capacity * kDeferredCallBytes;
    if (bytes > context_.info().max_storage_range)
      throw VulkanError(std::to_string(needed) + " insert calls cut short exceed " + context_.info().name +
                        "'s storage range (" + std::to_string(context_.info().max_storage_range) + " bytes)");
    std::array<VulkanBuffer, 2> grown{VulkanBuffer(context_, bytes), VulkanBuffer(context_, bytes)};
    deferred_ = std::move(grown);
    capacity_ = capacity;
  }

  // The resume rounds after a gather: each resumes the calls of one buffer,
  // those cut short again appended to the other. False when more were cut
  // short than the buffer holds (grown: the gather must run again).
  bool resume_all(const VulkanTechnique& t, VulkanBuildInfo& info) {
    std::size_t in = 0;
    std::uint64_t pending = deferred_[0].read<std::uint32_t>(1)[0];
    for (std::uint32_t round = 0; pending > 0; ++round) {
      if (pending > capacity_) {
        grow_deferred(pending);
        return false;
      }
      if (round >= kMaxResumeRounds)
        throw VulkanError(std::to_string(pending) + " insert calls still cut short after " +
                          std::to_string(kMaxResumeRounds) + " resume rounds");
      info.deferred += pending;
      ++info.resume_rounds;
      const std::size_t out = 1 - in;
      resume_->begin_recording();
      context_.submit_and_wait(
          [&](VkCommandBuffer cmd) {
            deferred_[out].record_zero(cmd);
            record_full_barrier(cmd);
            resume_->record(cmd, bindings(t, deferred_[in], deferred_[out]), static_cast<std::uint32_t>(pending),
                            pending);
            record_full_barrier(cmd);
          },
          "a Vulkan resume round");
      pending = deferred_[out].read<std::uint32_t>(1)[0];
      in = out;
    }
    return true;
  }

  // The sort pass over the screen (its pipeline made with the others).
  void sort(const VulkanTechnique& t) {
    if (!sort_) throw std::logic_error("a sort pass for " + to_string(t.config().technique) + ", made without one");
    sort_->begin_recording();
    context_.submit_and_wait(
        [&](VkCommandBuffer cmd) {
          sort_->record_screen(cmd, bindings(t, chunks_.front().buffer, deferred_[0]), t.config().buffer.screen);
          record_full_barrier(cmd);
        },
        "the Vulkan sort pass");
  }

  const VulkanContext& context_;
  VulkanBuffer params_, counters_, capture_;
  ComputePipeline insert_;
  std::unique_ptr<ComputePipeline> sort_;
  std::unique_ptr<ComputePipeline> resume_;   // emulated64's
  std::unique_ptr<ComputePipeline> fill_;     // the pass after a fill gather (the k-buffer's count)
  std::unique_ptr<ComputePipeline> resolve_;  // made when first asked for
  std::uint32_t resolve_samples_ = 0;         // the screen's samples it was made for
  std::vector<Chunk> chunks_;
  std::array<VulkanBuffer, 2> deferred_;  // the calls cut short: this round's, the next's
  std::uint64_t capacity_ = 0;            // calls each holds (0: native modes, a header only)
  std::uint64_t stream_size_ = 0;
};

}  // namespace

struct VulkanStreamBuilder::Pipelines {
  Technique technique;
  AtomicMode mode;
  StreamGather gather;
};

VulkanStreamBuilder::VulkanStreamBuilder(const VulkanContext& context) : context_(context) {}
VulkanStreamBuilder::~VulkanStreamBuilder() = default;

TechniqueBuild VulkanStreamBuilder::build(const TechniqueConfig& config, const OffsetSource& offsets,
                                          std::span<const Fragment> fragments, const ResizePolicy& policy,
                                          std::uint32_t max_attempts, VulkanBuildInfo* info, VulkanResolve* resolve) {
  const VulkanContext& context = context_;
  if (resolve && resolve->backgrounds.size() != config.buffer.screen.area())
    throw std::invalid_argument("the resolve needs one background colour per pixel of screen " +
                                config.buffer.screen.str() + " (" + std::to_string(config.buffer.screen.area()) +
                                "), given " + std::to_string(resolve->backgrounds.size()));
  if (max_attempts == 0) throw std::invalid_argument("at least one build attempt is needed");
  policy.validate();
  if (!runs_on_vulkan(config.technique))
    throw VulkanError("the Vulkan path does not run " + to_string(config.technique) + " yet (it runs " +
                      vulkan_technique_names() + ")");
  check_on_screen(fragments, config.buffer.screen);
  const std::optional<AtomicMode> mode = chosen_atomic_mode(context.info(), config.buffer.layout);
  if (!mode)
    throw VulkanError("--layout 64 on Vulkan: " + context.info().name + " has no 64-bit shader integers (shaderInt64)");
  VulkanBuildInfo local;
  VulkanBuildInfo& out = info ? *info : local;
  out = {};
  out.atomic_mode = to_string(*mode);
  out.device = context.info().name;
  // Lossless mode's rule of every path, asked before the first gather as
  // the OpenGL path does; the CPU's table for an unset one and its automatic pool.
  AttemptLimit limit = lossless_attempts(config, fragments, max_attempts);
  TechniqueConfig c = config;
  c.buffer.table = config.buffer.table_or_screen();
  const bool automatic_pool = uses_pool(c.technique) && c.pool_capacity == 0;
  if (automatic_pool) c.pool_capacity = policy.automatic(fragments.size());
  c.validate();  // the configuration's own message (std::invalid_argument) before any device work
  const std::uint32_t attempts = automatic_pool ? std::max<std::uint32_t>(limit.attempts, 2) : limit.attempts;
  if (!pipelines_ || pipelines_->technique != c.technique || pipelines_->mode != *mode) {
    pipelines_.reset();
    pipelines_.reset(new Pipelines{c.technique, *mode, StreamGather(context, c.technique, *mode)});
  }
  StreamGather& gather = pipelines_->gather;
  // Timed as the GL path times its build: the upload and every attempt's
  // gather with its counters; not the device's creation, the compilation,
  // the containers' allocation or the read-back into the CPU's container.
  const auto t0 = std::chrono::steady_clock::now();
  gather.upload(fragments);
  double timed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  TechniqueBuild b;
  std::uint64_t sized_for = 0;
  std::unique_ptr<VulkanTechnique> t;
  for (;;) {
    const auto a0 = std::chrono::steady_clock::now();
    t.reset();  // the last attempt's buffers go before the next one's are made
    t = make_vulkan_technique(context, c, offsets, *mode);
    gather.prepare(*t);
    const auto g0 = std::chrono::steady_clock::now();
    const Counters counters = gather.gather(*t, out);
    timed_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - g0).count();
    b.buffer = t->read_back();
    b.counters = counters;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a0).count();
    b.attempts.push_back({uses_table(c.technique) ? c.buffer.table : Extent{}, counters, t->capacity(), sized_for, ms});
    if (counters.failures() == 0 || b.attempts.size() >= attempts) break;
    const GrowthNeed need = attempt_need(*b.buffer, counters);
    const TechniqueConfig next = c.grown(policy, need);
    sized_for = need.count_for(c.technique);
    if (!next.limit().empty()) {
      b.growth_limited = true;
      break;
    }
    c = next;
  }
  // The too-deep pixel only where the first gather failed, as on the CPU.
  if (b.attempts.front().counters.failures() > 0) b.too_deep = std::move(limit.too_deep);
  out.build_ms = timed_ms;
  if (resolve) {
    gather.prepare_resolve(*t);  // compiled out of the timed span, as the gather's pipelines are
    const auto r0 = std::chrono::steady_clock::now();
    resolve->image = gather.resolve(*t, resolve->backgrounds);
    resolve->resolve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
  }
  return b;
}

TechniqueBuild build_technique_on_vulkan(const VulkanContext& context, const TechniqueConfig& config,
                                         const OffsetSource& offsets, std::span<const Fragment> fragments,
                                         const ResizePolicy& policy, std::uint32_t max_attempts,
                                         VulkanBuildInfo* info) {
  return VulkanStreamBuilder(context).build(config, offsets, fragments, policy, max_attempts, info);
}

TechniqueBuild build_and_resolve_on_vulkan(const VulkanContext& context, const TechniqueConfig& config,
                                           const OffsetSource& offsets, std::span<const Fragment> fragments,
                                           VulkanResolve& resolve, const ResizePolicy& policy,
                                           std::uint32_t max_attempts, VulkanBuildInfo* info) {
  return VulkanStreamBuilder(context).build(config, offsets, fragments, policy, max_attempts, info, &resolve);
}

}  // namespace habuffer::vk
