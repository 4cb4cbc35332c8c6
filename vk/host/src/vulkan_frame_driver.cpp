#include "habuffer/vk/vulkan_frame_driver.h"

#include <array>
#include <chrono>
#include <cstring>
#include <deque>
#include <map>
#include <stdexcept>
#include <thread>
#include <utility>

#include "habuffer/gl/module_id.h"
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

// The timestamps of a frame's slot.
enum Query : std::uint32_t { kFrameStart, kCleared, kGathered, kSorted, kResolveStart, kResolveEnd, kQueries };

// The storage image format qualifier of a host image's format ("" where the resolve cannot write it).
std::string image_qualifier(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM: return "rgba8";
    case VK_FORMAT_R16G16B16A16_SFLOAT: return "rgba16f";
    case VK_FORMAT_R32G32B32A32_SFLOAT: return "rgba32f";
    default: return "";
  }
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access, VkPipelineStageFlags dst,
                    VkAccessFlags dst_access) {
  VkMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  b.srcAccessMask = src_access;
  b.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

constexpr VkPipelineStageFlags kShaders = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags kShaderUse =
    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT;

// Earlier frames' shader and transfer work on the driver's buffers before this frame's transfers.
void barrier_before_transfer(VkCommandBuffer cmd) {
  memory_barrier(cmd, kShaders | VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

// Transfers and compute passes (the clear, a fill pass) before the shaders that read and write what they wrote.
void barrier_before_shaders(VkCommandBuffer cmd) {
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT, kShaders, kShaderUse);
}

// A gather's (or a compute pass's) writes before compute passes and transfers.
void barrier_after_shaders(VkCommandBuffer cmd) {
  memory_barrier(cmd, kShaders, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 kShaderUse | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

// Sets `event` once every earlier command has run, after a barrier that
// makes the counters' copy available to the host (the host reads the
// mapped, coherent slot once it sees the event set).
void record_host_event(VkCommandBuffer cmd, VkEvent event) {
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                 VK_ACCESS_HOST_READ_BIT);
  vkCmdSetEvent(cmd, event, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
}

// One container of the technique and its descriptor set (set 0 of every
// pipeline of the frame, the host's gather's included).
struct Container {
  const VulkanContext& context;
  std::unique_ptr<VulkanTechnique> technique;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;

  Container(const VulkanContext& c, std::unique_ptr<VulkanTechnique> t) : context(c), technique(std::move(t)) {}
  ~Container() {
    if (pool != VK_NULL_HANDLE) vkDestroyDescriptorPool(context.device(), pool, nullptr);
  }
  Container(const Container&) = delete;
  Container& operator=(const Container&) = delete;
};

// A frame recorded, until its report is read: the read-back of its
// counters, the events its command buffers set (after the copy, after its
// resolve), its timestamps, its resolve's image set and the container it used.
struct Slot {
  const VulkanContext& context;
  VkEvent event = VK_NULL_HANDLE;           // set after the counters' copy (every earlier command done)
  VkEvent resolved_event = VK_NULL_HANDLE;  // set after its resolve
  MappedBuffer readback;
  VkQueryPool queries = VK_NULL_HANDLE;
  VkDescriptorPool image_sets = VK_NULL_HANDLE;
  bool busy = false;      // recorded, its report not read
  bool resolved = false;  // a resolve was recorded after it (its timestamps awaited too)
  bool sorted = false;
  VulkanFrameReport report;  // what was known when it was recorded
  std::shared_ptr<Container> container;

  explicit Slot(const VulkanContext& c, bool timestamps) : context(c), readback(c, kCounterWords * 4) {
    const VkDevice d = c.device();
    try {
      VkEventCreateInfo ei{};
      ei.sType = VK_STRUCTURE_TYPE_EVENT_CREATE_INFO;
      check(vkCreateEvent(d, &ei, nullptr, &event), "creating a frame's event");
      check(vkCreateEvent(d, &ei, nullptr, &resolved_event), "creating a frame's resolve event");
      if (timestamps) {
        VkQueryPoolCreateInfo qi{};
        qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = kQueries;
        check(vkCreateQueryPool(d, &qi, nullptr, &queries), "creating a frame's timestamp queries");
      }
      const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1};
      VkDescriptorPoolCreateInfo pi{};
      pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
      pi.maxSets = 1;
      pi.poolSizeCount = 1;
      pi.pPoolSizes = &size;
      check(vkCreateDescriptorPool(d, &pi, nullptr, &image_sets), "creating a frame's image descriptor pool");
    } catch (...) {
      release();
      throw;
    }
  }
  ~Slot() { release(); }
  Slot(const Slot&) = delete;
  Slot& operator=(const Slot&) = delete;

  void release() {
    const VkDevice d = context.device();
    if (image_sets != VK_NULL_HANDLE) vkDestroyDescriptorPool(d, image_sets, nullptr);
    if (queries != VK_NULL_HANDLE) vkDestroyQueryPool(d, queries, nullptr);
    if (event != VK_NULL_HANDLE) vkDestroyEvent(d, event, nullptr);
    if (resolved_event != VK_NULL_HANDLE) vkDestroyEvent(d, resolved_event, nullptr);
    image_sets = VK_NULL_HANDLE;
    queries = VK_NULL_HANDLE;
    event = resolved_event = VK_NULL_HANDLE;
  }

  void timestamp(VkCommandBuffer cmd, Query q, VkPipelineStageFlagBits stage) const {
    if (queries != VK_NULL_HANDLE) vkCmdWriteTimestamp(cmd, stage, queries, q);
  }

  // Each timestamp and whether it has been written (availability).
  std::array<std::pair<std::uint64_t, bool>, kQueries> read_timestamps() const {
    std::array<std::pair<std::uint64_t, bool>, kQueries> out{};
    if (queries == VK_NULL_HANDLE) return out;
    std::array<std::uint64_t, 2 * kQueries> raw{};
    const VkResult r =
        vkGetQueryPoolResults(context.device(), queries, 0, kQueries, sizeof raw, raw.data(), 2 * sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    if (r != VK_SUCCESS && r != VK_NOT_READY) check(r, "reading a frame's timestamps");
    for (std::uint32_t q = 0; q < kQueries; ++q) out[q] = {raw[2 * q], raw[2 * q + 1] != 0};
    return out;
  }
};

}  // namespace

struct VulkanFrameDriver::State {
  const VulkanContext& context;
  TechniqueConfig given;  // as made (resize_screen changes its screen)
  OffsetSource offsets;
  VulkanFrameOptions options;
  AtomicMode mode = AtomicMode::Native32;
  bool automatic = false;     // no table or pool given: counted, then adaptive
  bool count_calls = false;   // the module counts its calls (a software device's loop budget)
  std::string defines;        // the variant's, before the fingerprint
  std::uint32_t module_id = 0;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VulkanBuffer params, counters, capture, stream, deferred;
  std::unique_ptr<ComputePipeline> sort, fill;
  std::map<std::string, std::unique_ptr<ComputePipeline>> resolves;  // by image format qualifier
  std::shared_ptr<Container> current;
  std::shared_ptr<Container> last_recorded;  // the container of the last recorded frame
  Slot* last_slot = nullptr;
  // The latest completed frame's slot and container, kept one frame more:
  // its command buffer may still run the host's commands after its event
  // (the frame after it sets its event only once every earlier command is done).
  Slot* latest_completed = nullptr;
  std::shared_ptr<Container> completed_hold;
  // What a frame's report says of its sizing, kept for the next frame when
  // recording it threw after the container was sized.
  VulkanFrameReport carried;
  bool forgotten = false;  // the last frame recorded was forgotten (forget_frames_in_flight)
  std::vector<std::unique_ptr<Slot>> slots;
  std::deque<Slot*> in_flight;  // oldest first
  std::vector<VulkanFrameReport> held;
  std::uint64_t frames = 0;
  bool needs_count = false;
  std::optional<std::uint64_t> sized_for_fragments;  // size_for's count, for the next frame's report
  std::optional<std::pair<std::uint64_t, GrowthNeed>> latest;  // the latest complete frame's need, not yet sized by
  std::uint64_t sizing_floor = 0;  // frames before this one size nothing (a count or a resize since)
  // The gather being recorded (bind() is valid only there).
  VkCommandBuffer gather_cmd = VK_NULL_HANDLE;
  bool bound = false;

  State(const VulkanContext& c, const TechniqueConfig& config, const OffsetSource& o, const VulkanFrameOptions& opt)
      : context(c), given(config), offsets(o), options(opt) {}

  ~State() {
    if (set_layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(context.device(), set_layout, nullptr);
  }

  [[nodiscard]] TechniqueConfig placeholder(const TechniqueConfig& c) const {
    // An automatic container's size until its count arrives.
    TechniqueConfig p = c;
    if (uses_table(p.technique)) p.buffer.table = p.buffer.table_or_screen();
    if (uses_pool(p.technique) && p.pool_capacity == 0) p.pool_capacity = options.policy.automatic(p.buffer.screen.area());
    return p;
  }

  std::shared_ptr<Container> make_container(const TechniqueConfig& c) {
    c.validate();
    auto out = std::make_shared<Container>(context, make_vulkan_technique(context, c, offsets, mode));
    const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ComputePipeline::kStorageBindings}};
    VkDescriptorPoolCreateInfo pi{};
    pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pi.maxSets = 1;
    pi.poolSizeCount = 2;
    pi.pPoolSizes = sizes;
    check(vkCreateDescriptorPool(context.device(), &pi, nullptr, &out->pool), "creating a container's descriptor pool");
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = out->pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout;
    check(vkAllocateDescriptorSets(context.device(), &ai, &out->set), "allocating a container's descriptor set");
    write_frame_set(context, out->set,
                    frame_bindings(*out->technique, FrameBuffers{&params, &counters, &capture, &stream, &deferred}),
                    "the frame's descriptor set");
    return out;
  }

  [[nodiscard]] std::string module_text(std::string_view header) const {
    std::string h = defines;
    if (count_calls) h += "#define HABUFFER_COUNT_CALLS\n";
    h += header;
    return vulkan_technique_module(given.technique, mode, gl::ShaderStage::Fragment, h);
  }

  void write_params(VkCommandBuffer cmd, std::uint32_t phase) const {
    ParamBlock p = frame_params(*current->technique, phase);
    p.habuffer_module_id = module_id;
    static_assert(sizeof(ParamBlock) % 4 == 0 && sizeof(ParamBlock) <= 65536, "vkCmdUpdateBuffer's limits");
    vkCmdUpdateBuffer(cmd, params.handle(), 0, sizeof p, &p);
  }

  // The host's gather, bind() allowed inside it; VulkanError where it bound no set.
  void run_gather(VkCommandBuffer cmd, const Gather& gather) {
    gather_cmd = cmd;
    bound = false;
    try {
      gather(cmd);
    } catch (...) {
      gather_cmd = VK_NULL_HANDLE;
      throw;
    }
    gather_cmd = VK_NULL_HANDLE;
    if (!bound)
      throw VulkanError("the gather bound no habuffer set: call VulkanFrameDriver::bind(cmd, layout) after binding "
                        "its pipeline");
  }

  // The counting gather of an automatic container (on the context's queue,
  // waited for), and the container sized for its count.
  void count_and_size(const Gather& gather, VulkanFrameReport& report) {
    context.submit_and_wait(
        [&](VkCommandBuffer cmd) {
          barrier_before_transfer(cmd);
          write_params(cmd, HABUFFER_PHASE_COUNT);
          counters.record_zero(cmd);
          barrier_before_shaders(cmd);
          run_gather(cmd, gather);
          barrier_after_shaders(cmd);
        },
        "the counting gather");
    const std::vector<std::uint32_t> words = counters.read<std::uint32_t>(kCounterWords);
    (void)counters_from_words(words);  // calls from another module refused
    size_for(stripe_tally(words)[HABUFFER_COUNTER_COUNTED]);
    report.resized = true;
  }

  // The automatic container for `fragments` (TechniqueConfig::sized_for);
  // counts of frames recorded before decide nothing.
  void size_for(std::uint64_t fragments) {
    if (fragments > UINT32_MAX)
      throw VulkanError("a frame of " + std::to_string(fragments) +
                        " fragments overflows the GPU path's 32-bit counters: draw fewer fragments per frame");
    TechniqueConfig wanted = given;
    wanted.buffer.screen = current->technique->config().buffer.screen;
    try {
      wanted = wanted.sized_for(options.policy, fragments);
      current = make_container(wanted);
    } catch (const std::exception& e) {
      throw VulkanError("sizing the " + to_string(given.technique) + " container for " + std::to_string(fragments) +
                        " fragments: " + e.what());
    }
    sized_for_fragments = fragments;
    carried = {};  // a container sized before this one is gone
    needs_count = false;
    latest.reset();
    sizing_floor = frames;
  }

  // Adaptive sizing from the latest complete frame's need (ResizePolicy::next).
  void adapt(VulkanFrameReport& report) {
    if (!(options.adaptive || automatic) || !latest || latest->first < sizing_floor) return;
    const auto [frame, need] = *std::exchange(latest, std::nullopt);
    TechniqueConfig next = current->technique->config();
    if (uses_table(next.technique))
      next.buffer.table = options.policy.next(next.buffer.table, next.buffer.screen, need.records);
    else if (uses_pool(next.technique))
      next.pool_capacity = options.policy.next(next.pool_capacity, need.nodes_requested);
    else
      return;  // fixed arrays and K layers keep their size
    if (next.buffer.table == current->technique->config().buffer.table &&
        next.pool_capacity == current->technique->config().pool_capacity)
      return;
    try {
      current = make_container(next);
    } catch (const std::exception&) {
      report.resize_limited = true;  // beyond the device's limits: the largest made so far kept
      return;
    }
    report.resized = true;
    report.sized_by_frame = frame;
    sizing_floor = frames;  // frames gathered into the old container size nothing more
  }

  Slot& acquire_slot() {
    if (in_flight.size() >= options.max_frames_in_flight)
      throw VulkanError(std::to_string(in_flight.size()) + " frames recorded have no report yet (max_frames_in_flight " +
                        std::to_string(options.max_frames_in_flight) +
                        "): submit them and read their reports (collect_reports) before recording more");
    for (const auto& s : slots)
      if (!s->busy && s.get() != latest_completed) return *s;
    slots.push_back(std::make_unique<Slot>(context, options.timestamps && context.info().timestamps));
    return *slots.back();
  }

  [[nodiscard]] bool ready(const Slot& s) const {
    if (vkGetEventStatus(context.device(), s.event) != VK_EVENT_SET) return false;
    if (s.resolved && vkGetEventStatus(context.device(), s.resolved_event) != VK_EVENT_SET) return false;
    if (s.queries == VK_NULL_HANDLE) return true;
    // Timestamps written at the bottom of the pipe may land after the event.
    const auto t = s.read_timestamps();
    for (Query q : {kFrameStart, kCleared, kGathered, kSorted})
      if (!t[q].second) return false;
    return !s.resolved || (t[kResolveStart].second && t[kResolveEnd].second);
  }

  // The report of a slot whose commands have run.
  VulkanFrameReport complete(Slot& s) {
    VulkanFrameReport r = s.report;
    const auto* mapped = static_cast<const std::uint32_t*>(s.readback.data());
    const std::vector<std::uint32_t> words(mapped, mapped + kCounterWords);
    s.busy = false;
    latest_completed = &s;
    std::shared_ptr<Container> container = std::move(s.container);
    completed_hold = container;
    r.counters = counters_from_words(words);
    const auto tally = stripe_tally(words);
    const Extent screen = r.config.buffer.screen;
    if (s.sorted && tally[HABUFFER_COUNTER_SORT_DONE] != screen.area())
      throw VulkanError("the driver ended " + std::to_string(screen.area() - tally[HABUFFER_COUNTER_SORT_DONE]) +
                        " per-pixel sorts of frame " + std::to_string(r.index) + " early (its loop budget)");
    if (count_calls) {
      // Calls the driver ended without an outcome: counted failed at the iteration limit (SPEC invariant 1).
      const std::uint64_t made = std::uint64_t{words[HABUFFER_COUNTER_CALLS]} + tally[HABUFFER_COUNTER_OFF_SCREEN];
      if (made > r.counters.fragments) {
        r.ended_by_driver = made - r.counters.fragments;
        r.counters.fragments += r.ended_by_driver;
        r.counters.failed_iter += r.ended_by_driver;
      }
    }
    container->technique->gathered(words);
    if (s.queries != VK_NULL_HANDLE) {
      const auto t = s.read_timestamps();
      const double ns = context.info().timestamp_period_ns;
      const auto span = [&](Query a, Query b) {
        return t[a].second && t[b].second && t[b].first >= t[a].first
                   ? static_cast<double>(t[b].first - t[a].first) * ns / 1e6
                   : 0.0;
      };
      r.clear_ms = span(kFrameStart, kCleared);
      r.gather_ms = span(kCleared, kGathered);
      r.sort_ms = span(kGathered, kSorted);
      r.resolve_ms = span(kResolveStart, kResolveEnd);
    }
    if (r.index >= sizing_floor && (!latest || latest->first < r.index))
      latest = {r.index, GrowthNeed{words[HABUFFER_COUNTER_NODES], 0, r.counters.records_needed()}};
    return r;
  }

  // The reports of frames that have run, oldest first, into `held` (a
  // report that throws, a frame refused, leaves those before it there).
  void collect_ready() {
    while (!in_flight.empty() && ready(*in_flight.front())) {
      Slot* s = in_flight.front();
      in_flight.pop_front();
      held.push_back(complete(*s));
    }
  }

  // Every frame in flight waited for (at most timeout_ms in all), into `held`.
  void wait_all(std::uint64_t timeout_ms) {
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
      collect_ready();
      if (in_flight.empty()) return;
      const auto waited = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0);
      if (static_cast<std::uint64_t>(waited.count()) >= timeout_ms)
        throw VulkanError(std::to_string(in_flight.size()) + " frames recorded (the oldest frame " +
                          std::to_string(in_flight.front()->report.index) + ") had not run after " +
                          std::to_string(timeout_ms) + " ms: a frame recorded but never submitted never does");
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  ComputePipeline& resolve_pipeline(const std::string& qualifier) {
    auto& p = resolves[qualifier];
    if (!p) {
      const std::string name = to_string(given.technique) + " resolve into an " + qualifier + " image (Vulkan)";
      p = std::make_unique<ComputePipeline>(
          context,
          compile_to_spirv(vulkan_resolve_image_compute(given.technique, mode, qualifier, defines),
                           SpirvStage::Compute, name),
          name, PipelineSets{VK_SHADER_STAGE_FRAGMENT_BIT, true});
    }
    return *p;
  }
};

VulkanFrameDriver::VulkanFrameDriver(const VulkanContext& context, const TechniqueConfig& config,
                                     const OffsetSource& offsets, const VulkanFrameOptions& options)
    : s_(std::make_unique<State>(context, config, offsets, options)) {
  State& s = *s_;
  options.policy.validate();
  if (options.max_frames_in_flight == 0)
    throw std::invalid_argument("VulkanFrameOptions::max_frames_in_flight must be at least 1");
  if (config.buffer.screen.area() == 0) throw std::invalid_argument("the frame driver needs a screen of at least 1x1");
  if (config.buffer.samples > 1)
    throw VulkanError("the Vulkan frame driver runs screens of one sample (given " +
                      std::to_string(config.buffer.samples) + "): multisampled host gathers are not recorded yet");
  if (!runs_on_vulkan(config.technique))
    throw VulkanError("the Vulkan path does not run " + to_string(config.technique) + " yet (it runs " +
                      vulkan_technique_names() + ")");
  const std::optional<AtomicMode> mode = chosen_atomic_mode(context.info(), config.buffer.layout);
  if (!mode)
    throw VulkanError("--layout 64 on Vulkan: " + context.info().name + " has no 64-bit shader integers (shaderInt64)");
  if (*mode == AtomicMode::Emulated64)
    throw VulkanError("the Vulkan frame driver runs native64 and native32, not emulated64 (its resume rounds are read "
                      "between passes, which a host's command buffer cannot hold): use a device with "
                      "shaderBufferInt64Atomics, or layout 32");
  s.mode = *mode;
  s.automatic = (uses_table(config.technique) && config.buffer.table.area() == 0) ||
                (uses_pool(config.technique) && config.pool_capacity == 0);
  s.needs_count = s.automatic && options.count_first_frame;
  s.count_calls = context.info().software;
  s.defines = frame_variant_defines(s.mode, context.info());
  const TechniqueConfig first = s.placeholder(config);
  first.validate();  // the configuration's own message before any device work
  s.module_id = gl::module_fingerprint(s.module_text({}));
  s.set_layout = make_frame_set_layout(context, VK_SHADER_STAGE_FRAGMENT_BIT, "the frame driver");
  constexpr std::uint64_t kAppendHeaderBytes = HABUFFER_APPEND_HEADER_WORDS * 4;
  s.params = VulkanBuffer(context, sizeof(ParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  s.counters = VulkanBuffer(context, kCounterWords * 4);
  s.capture = VulkanBuffer(context, kAppendHeaderBytes + sizeof(Fragment));
  s.stream = VulkanBuffer(context, sizeof(Fragment));
  s.deferred = VulkanBuffer(context, kAppendHeaderBytes);
  s.current = s.make_container(first);
  const VulkanTechnique& t = *s.current->technique;
  const std::string what = " (Vulkan, " + to_string(s.mode) + ")";
  if (t.sorts_after_gather()) {
    const std::string name = to_string(config.technique) + " sort" + what;
    s.sort = std::make_unique<ComputePipeline>(
        context, compile_to_spirv(vulkan_sort_compute(config.technique, s.mode, s.defines), SpirvStage::Compute, name),
        name, PipelineSets{VK_SHADER_STAGE_FRAGMENT_BIT, false});
  }
  if (t.fills_before_insert()) {
    const std::string name = to_string(config.technique) + " fill pass" + what;
    s.fill = std::make_unique<ComputePipeline>(
        context, compile_to_spirv(t.fill_pass_compute(s.defines), SpirvStage::Compute, name), name,
        PipelineSets{VK_SHADER_STAGE_FRAGMENT_BIT, false});
  }
}

VulkanFrameDriver::~VulkanFrameDriver() {
  // Every frame in flight waited for (10 s in all; a frame refused, or never
  // submitted, ends its wait), then the queue: the host's command buffers
  // may still hold commands after a frame's last event that use our objects.
  State& s = *s_;
  const auto t0 = std::chrono::steady_clock::now();
  const auto limit = std::chrono::seconds(10);
  while (!s.in_flight.empty() && std::chrono::steady_clock::now() - t0 < limit) {
    try {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(limit - (std::chrono::steady_clock::now() - t0));
      s.wait_all(static_cast<std::uint64_t>(std::max<std::int64_t>(left.count(), 1)));
    } catch (...) {
      // A refused frame's error has nowhere to go here; the wait goes on.
    }
  }
  vkQueueWaitIdle(s.context.queue());
}

AtomicMode VulkanFrameDriver::mode() const { return s_->mode; }
Extent VulkanFrameDriver::screen() const { return s_->current->technique->config().buffer.screen; }
TechniqueConfig VulkanFrameDriver::config() const { return s_->current->technique->config(); }
const VulkanFrameOptions& VulkanFrameDriver::options() const { return s_->options; }
VkDescriptorSetLayout VulkanFrameDriver::set_layout() const { return s_->set_layout; }
std::size_t VulkanFrameDriver::frames_in_flight() const { return s_->in_flight.size(); }

std::string VulkanFrameDriver::module_source(std::string_view header) const {
  return s_->module_text(gl::module_id_define(s_->module_id) + std::string(header));
}

std::vector<std::uint32_t> VulkanFrameDriver::compile_gather_fragment(std::string_view main_source) const {
  return compile_to_spirv(module_source() + std::string(main_source), SpirvStage::Fragment,
                          "the host's gather fragment shader");
}

void VulkanFrameDriver::size_for(std::uint64_t fragments) {
  State& s = *s_;
  if (!s.automatic)
    throw std::invalid_argument("size_for: this " + to_string(s.given.technique) +
                                " container was given its size (an automatic one is made without a table or pool)");
  s.size_for(fragments);
}

void VulkanFrameDriver::bind(VkCommandBuffer cmd, VkPipelineLayout layout) {
  State& s = *s_;
  if (s.gather_cmd == VK_NULL_HANDLE)
    throw VulkanError("VulkanFrameDriver::bind outside a gather: bind the frame's set inside the gather record_frame "
                      "calls");
  if (cmd != s.gather_cmd) throw VulkanError("VulkanFrameDriver::bind: not the command buffer the gather records");
  if (layout == VK_NULL_HANDLE) throw std::invalid_argument("VulkanFrameDriver::bind: no pipeline layout given");
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &s.current->set, 0, nullptr);
  s.bound = true;
}

void VulkanFrameDriver::record_frame(VkCommandBuffer cmd, const Gather& gather) {
  State& s = *s_;
  if (cmd == VK_NULL_HANDLE) throw std::invalid_argument("record_frame: no command buffer given");
  if (!gather) throw std::invalid_argument("record_frame: no gather given");
  if (s.gather_cmd != VK_NULL_HANDLE) throw VulkanError("record_frame inside a gather");
  s.collect_ready();
  Slot& slot = s.acquire_slot();  // before any sizing: a refusal here changes nothing
  // This frame's sizing (and what an earlier frame that threw had sized).
  VulkanFrameReport report = std::exchange(s.carried, {});
  report.index = s.frames;
  try {
    if (s.needs_count) {
      s.count_and_size(gather, report);
    } else if (s.sized_for_fragments) {
      report.resized = true;  // size_for since the last frame
    } else {
      s.adapt(report);
    }
    if (s.sized_for_fragments) report.counted_fragments = std::exchange(s.sized_for_fragments, std::nullopt);
    check(vkResetEvent(s.context.device(), slot.event), "resetting a frame's event");
    check(vkResetEvent(s.context.device(), slot.resolved_event), "resetting a frame's resolve event");
    check(vkResetDescriptorPool(s.context.device(), slot.image_sets, 0), "resetting a frame's image set");
    const Container& c = *s.current;
    const VulkanTechnique& t = *c.technique;
    if (slot.queries != VK_NULL_HANDLE) vkCmdResetQueryPool(cmd, slot.queries, 0, kQueries);
    slot.timestamp(cmd, kFrameStart, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
    barrier_before_transfer(cmd);
    s.write_params(cmd, t.fills_before_insert() ? HABUFFER_PHASE_FILL : HABUFFER_PHASE_INSERT);
    t.record_clear(cmd);
    s.counters.record_zero(cmd);
    barrier_before_shaders(cmd);
    slot.timestamp(cmd, kCleared, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    const std::array<VkDescriptorSet, 1> sets{c.set};
    if (t.fills_before_insert()) {
      // The k-buffer's occupancy map: a gather that inserts nothing, its count pass, then the insert gather.
      s.run_gather(cmd, gather);
      barrier_after_shaders(cmd);
      s.fill->record_screen_with(cmd, sets, t.config().buffer.screen);
      barrier_after_shaders(cmd);
      s.write_params(cmd, HABUFFER_PHASE_INSERT);
      barrier_before_shaders(cmd);
    }
    s.run_gather(cmd, gather);
    barrier_after_shaders(cmd);
    slot.timestamp(cmd, kGathered, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    slot.sorted = t.sorts_after_gather();
    if (slot.sorted) {
      s.sort->record_screen_with(cmd, sets, t.config().buffer.screen);
      barrier_after_shaders(cmd);
    }
    slot.timestamp(cmd, kSorted, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    const VkBufferCopy region{0, 0, kCounterWords * 4};
    vkCmdCopyBuffer(cmd, s.counters.handle(), slot.readback.handle(), 1, &region);
    record_host_event(cmd, slot.event);
    report.config = t.config();
    report.capacity = t.capacity();
  } catch (...) {
    // The host discards this command buffer; the next frame's report says
    // how its container was sized.
    s.carried.resized = report.resized;
    s.carried.sized_by_frame = report.sized_by_frame;
    s.carried.counted_fragments = report.counted_fragments;
    s.carried.resize_limited = report.resize_limited;
    throw;
  }
  slot.report = report;
  slot.container = s.current;
  slot.resolved = false;
  slot.busy = true;
  s.in_flight.push_back(&slot);
  s.last_slot = &slot;
  s.forgotten = false;
  s.last_recorded = s.current;
  ++s.frames;
}

void VulkanFrameDriver::record_resolve(VkCommandBuffer cmd, const HostImage& target) {
  State& s = *s_;
  if (cmd == VK_NULL_HANDLE) throw std::invalid_argument("record_resolve: no command buffer given");
  if (!s.last_recorded) throw std::logic_error("record_resolve before any record_frame: there are no lists to resolve");
  if (target.image == VK_NULL_HANDLE || target.view == VK_NULL_HANDLE)
    throw std::invalid_argument("record_resolve: the host image needs its image and a view");
  const std::string qualifier = image_qualifier(target.format);
  if (qualifier.empty())
    throw std::invalid_argument("record_resolve: the host image's format (VkFormat " +
                                std::to_string(static_cast<int>(target.format)) +
                                ") is not one the resolve writes (R8G8B8A8_UNORM, R16G16B16A16_SFLOAT, "
                                "R32G32B32A32_SFLOAT)");
  const Container& c = *s.last_recorded;
  const Extent screen = c.technique->config().buffer.screen;
  if (target.size != screen)
    throw std::invalid_argument("record_resolve: the host image is " + target.size.str() + ", the screen " +
                                screen.str());
  if (target.layout == VK_IMAGE_LAYOUT_UNDEFINED || target.layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
    throw std::invalid_argument("record_resolve: the host image's layout is undefined: its content, the background "
                                "the lists are composited over, would be lost");
  ComputePipeline& pipeline = s.resolve_pipeline(qualifier);
  Slot* slot = s.last_slot != nullptr && s.last_slot->busy ? s.last_slot : nullptr;
  if (slot == nullptr && s.forgotten)
    throw VulkanError("record_resolve: the last frame was forgotten (forget_frames_in_flight): record a frame first");
  if (slot == nullptr)
    throw VulkanError("record_resolve: the last frame's report was read already: resolve a frame before its report "
                      "is collected (record_frame, record_resolve, submit, then collect_reports)");
  if (slot->resolved)
    throw std::logic_error("record_resolve: frame " + std::to_string(slot->report.index) +
                           " was resolved already (one resolve a frame)");
  VkDescriptorPool pool = slot->image_sets;
  VkDescriptorSetLayout image_layout = pipeline.image_set_layout();
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &image_layout;
  VkDescriptorSet image_set = VK_NULL_HANDLE;
  check(vkAllocateDescriptorSets(s.context.device(), &ai, &image_set), "record_resolve: the image's descriptor set");
  const VkDescriptorImageInfo info{VK_NULL_HANDLE, target.view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = image_set;
  write.dstBinding = 0;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  write.pImageInfo = &info;
  vkUpdateDescriptorSets(s.context.device(), 1, &write, 0, nullptr);

  VkImageMemoryBarrier to_general{};
  to_general.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  to_general.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  to_general.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  to_general.oldLayout = target.layout;
  to_general.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  to_general.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_general.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_general.image = target.image;
  to_general.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  // The frame's writes (its gather, its sort) before the resolve reads them, with the image's move.
  VkMemoryBarrier lists{};
  lists.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  lists.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  lists.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &lists, 0,
                       nullptr, 1, &to_general);
  slot->timestamp(cmd, kResolveStart, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
  const std::array<VkDescriptorSet, 2> sets{c.set, image_set};
  pipeline.record_screen_with(cmd, sets, screen);
  slot->timestamp(cmd, kResolveEnd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
  VkImageMemoryBarrier back = to_general;
  back.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  back.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  back.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
  back.newLayout = target.layout;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &back);
  vkCmdSetEvent(cmd, slot->resolved_event, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);  // the frame's report waits for it
  slot->resolved = true;
}

std::vector<VulkanFrameReport> VulkanFrameDriver::collect_reports() {
  State& s = *s_;
  s.collect_ready();  // a refused frame throws; the reports before it stay for the next call
  return std::exchange(s.held, {});
}

std::vector<VulkanFrameReport> VulkanFrameDriver::finish_reports(std::uint64_t timeout_ms) {
  State& s = *s_;
  s.wait_all(timeout_ms);
  return std::exchange(s.held, {});
}

void VulkanFrameDriver::forget_frames_in_flight() {
  State& s = *s_;
  s.collect_ready();
  // The next report says how its container was sized, where a forgotten frame sized it.
  for (Slot* slot : s.in_flight) {
    if (slot->report.resized && !s.carried.resized) {
      s.carried.resized = true;
      s.carried.sized_by_frame = slot->report.sized_by_frame;
      s.carried.counted_fragments = slot->report.counted_fragments;
    }
    s.carried.resize_limited = s.carried.resize_limited || slot->report.resize_limited;
    slot->busy = false;
    slot->container.reset();
  }
  s.in_flight.clear();
  s.last_slot = nullptr;
  s.forgotten = true;
}

std::unique_ptr<FragmentBuffer> VulkanFrameDriver::read_back() const {
  const State& s = *s_;
  if (!s.in_flight.empty())
    throw VulkanError("read_back: " + std::to_string(s.in_flight.size()) +
                      " frames are in flight: finish_reports() first");
  if (!s.last_recorded) throw std::logic_error("read_back before any record_frame: there is no frame to read");
  return s.last_recorded->technique->read_back();
}

void VulkanFrameDriver::resize_screen(Extent screen) {
  State& s = *s_;
  if (screen.area() == 0) throw std::invalid_argument("resize_screen: a screen of at least 1x1 is needed, given " + screen.str());
  if (screen == s.current->technique->config().buffer.screen) return;  // nothing changed: nothing counted again
  TechniqueConfig next = s.given;
  next.buffer.screen = screen;
  next = s.placeholder(next);
  next.validate();  // nothing changes when the configuration's rules refuse it
  s.wait_all(10000);  // their reports kept for collect_reports
  s.current = s.make_container(next);
  s.given.buffer.screen = screen;
  s.needs_count = s.automatic && s.options.count_first_frame;
  s.sized_for_fragments.reset();
  s.carried = {};  // what frames before the resize had sized is gone with their container
  s.latest.reset();
  s.sizing_floor = s.frames;
}

}  // namespace habuffer::vk
