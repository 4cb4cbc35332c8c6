#include "habuffer/gl/techniques/paged_lists/gl_paged_lists.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl_params.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "sort_pass.h"

namespace habuffer::gl {
namespace {

constexpr std::uint64_t kNodeBytes = sizeof(glm::uvec2) + 4;  // entry and link

// One page per pixel: where an automatic pool starts.
std::uint64_t page_per_pixel(Extent screen) {
  return std::max<std::uint64_t>(screen.area(), 1) * kPagedListsPageNodes;
}

// pool_capacity 0 asks for an automatic pool (see the header).
TechniqueConfig with_pool(TechniqueConfig c) {
  if (c.pool_capacity == 0) c.pool_capacity = page_per_pixel(c.buffer.screen);
  return c;
}

}  // namespace

struct GlPagedLists::Gpu {
  GLuint heads = 0, nodes = 0, links = 0;
  std::unique_ptr<SortPass> sort;
  ~Gpu() {
    for (GLuint* b : {&heads, &nodes, &links}) delete_buffer(*b);
  }
};

GlPagedLists::GlPagedLists(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(Technique::PagedLists, mode, bindings,
                  validated_as(with_pool(config), Technique::PagedLists).buffer.screen),
      config_(validated_as(with_pool(config), Technique::PagedLists)),
      auto_pool_(config.pool_capacity == 0),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  check_storage_fits(screen().area() * 4, "the head image of screen " + screen().str());
  gpu_->heads = create_buffer(screen().area() * 4);
  allocate_pool(config_.pool_capacity);
  gpu_->sort = std::make_unique<SortPass>(Technique::PagedLists, mode, bindings);
}

GlPagedLists::~GlPagedLists() = default;

bool GlPagedLists::fit_automatic_size(const TechniqueConfig& wanted) {
  const std::uint64_t fitted = std::min<std::uint64_t>(wanted.pool_capacity, max_storage_bytes() / sizeof(glm::uvec2));
  resize_pool(fitted);
  return fitted != wanted.pool_capacity;
}

void GlPagedLists::allocate_pool(std::uint64_t nodes) {
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

void GlPagedLists::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  const std::uint64_t from = this->screen().area(), to = screen.area();
  const std::uint64_t scaled = (config_.pool_capacity * to + from - 1) / from;
  next.pool_capacity = std::max<std::uint64_t>(scaled, auto_pool_ ? page_per_pixel(screen) : 1);
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
  check_gl_errors("resizing the paged lists' screen");
  std::swap(gpu_->heads, fresh.heads);
  if (fresh.nodes != 0) {
    std::swap(gpu_->nodes, fresh.nodes);
    std::swap(gpu_->links, fresh.links);
  }
  config_ = next;
  // The last request was made on the old screen: SPEC 8's rule waits for a frame of the new one.
  has_request_ = false;
  last_requested_ = 0;
}

void GlPagedLists::resize_pool(std::uint64_t nodes) {
  if (nodes != config_.pool_capacity) allocate_pool(nodes);
}

void GlPagedLists::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlPagedLists::bind() const {
  const GlBindings& b = bindings();
  bind_at(GL_SHADER_STORAGE_BUFFER, b.table, gpu_->heads);    // HABUFFER_BINDING_HEADS
  bind_at(GL_SHADER_STORAGE_BUFFER, b.max_age, gpu_->nodes);  // HABUFFER_BINDING_NODES
  bind_at(GL_SHADER_STORAGE_BUFFER, b.offsets, gpu_->links);  // HABUFFER_BINDING_LINKS
}

std::string GlPagedLists::pool_limit(std::uint64_t nodes) const {
  TechniqueConfig c = config_;
  c.pool_capacity = nodes;
  if (std::string why = c.limit(); !why.empty()) return why;
  if (nodes * sizeof(glm::uvec2) > max_storage_bytes())
    return "a node pool of " + std::to_string(nodes) + " nodes exceeds this OpenGL's shader-storage buffers";
  return {};
}

void GlPagedLists::begin_frame(FrameReport& report, const GlFrameOptions& options) {
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

void GlPagedLists::before_gather() {
  zero_buffer(gpu_->heads);  // the node counter is zeroed with the driver's tallies
}

PassTiming GlPagedLists::after_gather(bool finish_timing) { return gpu_->sort->run(screen(), finish_timing); }

void GlPagedLists::gathered(const FrameReport& report) {
  last_requested_ = report.nodes_requested;
  has_request_ = true;
}

bool GlPagedLists::grow(const FrameReport& report, const GlFrameOptions& options) {
  // The counter counted every page asked for, in nodes: a pool of that size holds the frame.
  const std::uint64_t next = config_.grown(options.policy, report.nodes_requested, 0).pool_capacity;
  if (!pool_limit(next).empty()) return false;
  allocate_pool(next);
  return true;
}

std::uint64_t GlPagedLists::memory_bytes() const {
  return screen().area() * 4 + config_.pool_capacity * kNodeBytes;
}

std::unique_ptr<FragmentBuffer> GlPagedLists::read_back() const {
  auto lists = std::make_unique<PagedLists>(config_);
  const std::vector<std::uint32_t> heads = read_words(gpu_->heads, screen().area());
  std::vector<glm::uvec2> entries(config_.pool_capacity);
  glGetNamedBufferSubData(gpu_->nodes, 0, static_cast<GLsizeiptr>(entries.size() * sizeof(glm::uvec2)), entries.data());
  const std::vector<std::uint32_t> links = read_words(gpu_->links, config_.pool_capacity);
  lists->import_state(heads, entries, links, last_requested_);
  return lists;
}

}  // namespace habuffer::gl
