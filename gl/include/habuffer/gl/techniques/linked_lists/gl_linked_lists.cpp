#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl_params.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "sort_pass.h"

namespace habuffer::gl {
namespace {

constexpr std::uint64_t kNodeBytes = sizeof(glm::uvec2) + 4;  // entry and link

// pool_capacity 0 asks for an automatic pool: it starts at one node per
// pixel (the API has no counting pass, as render has), a frame that dropped
// is gathered again at once into a pool of the nodes it asked for, and
// SPEC 8's rule adapts it every frame.
TechniqueConfig with_pool(TechniqueConfig c) {
  if (c.pool_capacity == 0) c.pool_capacity = std::max<std::uint64_t>(c.buffer.screen.area(), 1);
  return c;
}

}  // namespace

struct GlLinkedLists::Gpu {
  GLuint heads = 0, nodes = 0, links = 0, saturation = 0;
  std::unique_ptr<SortPass> sort;
  ~Gpu() {
    for (GLuint* b : {&heads, &nodes, &links, &saturation}) delete_buffer(*b);
  }
};

GlLinkedLists::GlLinkedLists(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(lists_flavour(config.technique), mode, bindings,
                  validated_as(with_pool(config), lists_flavour(config.technique)).buffer.screen),
      config_(validated_as(with_pool(config), lists_flavour(config.technique))),
      auto_pool_(config.pool_capacity == 0),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  check_storage_fits(screen().area() * 4, "the head image of screen " + screen().str());
  gpu_->heads = create_buffer(screen().area() * 4);
  allocate_pool(config_.pool_capacity);
  if (config_.buffer.saturation) gpu_->saturation = create_buffer(screen().area() * 4);
  if (!sorted_on_insert()) gpu_->sort = std::make_unique<SortPass>(Technique::Lists, mode, bindings);
}

bool GlLinkedLists::fit_automatic_size(const TechniqueConfig& wanted) {
  const std::uint64_t fitted = std::min<std::uint64_t>(wanted.pool_capacity, max_storage_bytes() / sizeof(glm::uvec2));
  resize_pool(fitted);
  return fitted != wanted.pool_capacity;
}

GlLinkedLists::~GlLinkedLists() = default;

void GlLinkedLists::allocate_pool(std::uint64_t nodes) {
  TechniqueConfig c = config_;
  c.pool_capacity = nodes;
  c.validate();
  check_storage_fits(nodes * sizeof(glm::uvec2), "a node pool of " + std::to_string(nodes) + " nodes");
  delete_buffer(gpu_->nodes);
  delete_buffer(gpu_->links);
  gpu_->nodes = create_buffer(nodes * sizeof(glm::uvec2));
  gpu_->links = create_buffer(nodes * 4);
  config_.pool_capacity = nodes;
}

void GlLinkedLists::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  const std::uint64_t from = this->screen().area(), to = screen.area();
  // The pool holds fragments, which grow with the area: scaled by its ratio
  // (rounded up; the automatic pool at least one node per pixel, as a fresh
  // one starts), or kept when the scaled pool is beyond the limits.
  const std::uint64_t scaled = (config_.pool_capacity * to + from - 1) / from;
  next.pool_capacity = std::max<std::uint64_t>(scaled, auto_pool_ ? to : 1);
  if (!pool_limit(next.pool_capacity).empty()) next.pool_capacity = config_.pool_capacity;
  next.validate();
  if (const std::string why = pool_limit(next.pool_capacity); !why.empty()) throw GlError(why);
  check_storage_fits(to * 4, "the head image of screen " + screen.str());
  // Made before the old ones go (fresh's destructor frees them on a throw).
  Gpu fresh;
  fresh.heads = create_buffer(to * 4);
  if (next.pool_capacity != config_.pool_capacity) {
    fresh.nodes = create_buffer(next.pool_capacity * sizeof(glm::uvec2));
    fresh.links = create_buffer(next.pool_capacity * 4);
  }
  if (next.buffer.saturation) fresh.saturation = create_buffer(to * 4);
  check_gl_errors("resizing the lists' screen");
  std::swap(gpu_->heads, fresh.heads);
  std::swap(gpu_->saturation, fresh.saturation);
  if (fresh.nodes != 0) {
    std::swap(gpu_->nodes, fresh.nodes);
    std::swap(gpu_->links, fresh.links);
  }
  config_ = next;
  // The last request was made on the old screen: SPEC 8's rule waits for a
  // frame of the new one.
  has_request_ = false;
  last_requested_ = 0;
}

void GlLinkedLists::resize_pool(std::uint64_t nodes) {
  if (nodes != config_.pool_capacity) allocate_pool(nodes);
}

void GlLinkedLists::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlLinkedLists::bind() const {
  const GlBindings& b = bindings();
  bind_at(GL_SHADER_STORAGE_BUFFER, b.table, gpu_->heads);   // HABUFFER_BINDING_HEADS
  bind_at(GL_SHADER_STORAGE_BUFFER, b.max_age, gpu_->nodes);  // HABUFFER_BINDING_NODES
  bind_at(GL_SHADER_STORAGE_BUFFER, b.offsets, gpu_->links);  // HABUFFER_BINDING_LINKS
  if (gpu_->saturation != 0) bind_at(GL_SHADER_STORAGE_BUFFER, b.saturation, gpu_->saturation);
}

std::string GlLinkedLists::pool_limit(std::uint64_t nodes) const {
  TechniqueConfig c = config_;
  c.pool_capacity = nodes;
  if (std::string why = c.limit(); !why.empty()) return why;
  if (nodes * sizeof(glm::uvec2) > max_storage_bytes())
    return "a node pool of " + std::to_string(nodes) + " nodes exceeds this OpenGL's shader-storage buffers";
  return {};
}

void GlLinkedLists::begin_frame(FrameReport& report, const GlFrameOptions& options) {
  if (!(options.adaptive || auto_pool_) || !has_request_) return;
  // SPEC 8's rule on the pool: its use is the nodes the last frame asked for.
  const std::uint64_t next = options.policy.next(config_.pool_capacity, last_requested_);
  if (next == config_.pool_capacity) return;
  if (!pool_limit(next).empty()) {
    report.resize_limited = true;
    return;
  }
  allocate_pool(next);
  report.resized = true;
}

void GlLinkedLists::before_gather() {
  zero_buffer(gpu_->heads);  // the node counter is zeroed with the driver's tallies
  if (gpu_->saturation != 0) zero_buffer(gpu_->saturation);
}

PassTiming GlLinkedLists::after_gather(bool finish_timing) {
  if (!gpu_->sort) return {};
  return gpu_->sort->run(screen(), finish_timing);
}

void GlLinkedLists::gathered(const FrameReport& report) {
  last_requested_ = report.nodes_requested;
  has_request_ = true;
}

bool GlLinkedLists::grow(const FrameReport& report, const GlFrameOptions& options) {
  // The counter counted every node asked for: a pool of that size holds the frame.
  const std::uint64_t next = config_.grown(options.policy, report.nodes_requested, 0).pool_capacity;
  if (!pool_limit(next).empty()) return false;
  allocate_pool(next);
  return true;
}

std::uint64_t GlLinkedLists::memory_bytes() const {
  return screen().area() * (config_.buffer.saturation ? 8 : 4) + config_.pool_capacity * kNodeBytes;
}

std::unique_ptr<FragmentBuffer> GlLinkedLists::read_back() const {
  auto lists = std::make_unique<LinkedLists>(config_);
  const std::vector<std::uint32_t> heads = read_words(gpu_->heads, screen().area());
  std::vector<glm::uvec2> entries(config_.pool_capacity);
  glGetNamedBufferSubData(gpu_->nodes, 0, static_cast<GLsizeiptr>(entries.size() * sizeof(glm::uvec2)), entries.data());
  const std::vector<std::uint32_t> links = read_words(gpu_->links, config_.pool_capacity);
  lists->import_state(heads, entries, links, last_requested_);
  return lists;
}

}  // namespace habuffer::gl
