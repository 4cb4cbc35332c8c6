#include "habuffer/gl/techniques/linked_lists/gl_linked_lists.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "sort_pass.h"

namespace habuffer::gl {

struct GlLinkedLists::Gpu {
  GlStorage heads, nodes, links, saturation;
  std::unique_ptr<SortPass> sort;
};

namespace {

// Validated as `kind`'s technique, with the automatic pool's first size (a
// page per pixel) where pool_capacity is 0.
TechniqueConfig validated_pool(TechniqueConfig c, const GlNodeListKind& kind) {
  if (c.pool_capacity == 0)
    c.pool_capacity = std::max<std::uint64_t>(c.buffer.screen.area(), 1) * kind.page_nodes;
  return validated_as(c, kind.technique);
}

constexpr GlNodeListKind kListsKind{Technique::Lists, 1, true, import_node_lists<LinkedLists>};
constexpr GlNodeListKind kSortedListsKind{Technique::SortedLists, 1, false, import_node_lists<LinkedLists>};

}  // namespace

const GlNodeListKind& lists_kind() { return kListsKind; }
const GlNodeListKind& sorted_lists_kind() { return kSortedListsKind; }

GlLinkedLists::GlLinkedLists(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlLinkedLists(config, lists_flavour(config.technique) == Technique::SortedLists ? kSortedListsKind : kListsKind,
                    mode, bindings) {}

GlLinkedLists::GlLinkedLists(const TechniqueConfig& config, const GlNodeListKind& kind, AtomicMode mode,
                             const GlBindings& bindings)
    : GlTechnique(kind.technique, mode, bindings, validated_pool(config, kind).buffer.screen,
                  config.buffer.samples),
      kind_(kind),
      config_(validated_pool(config, kind)),
      auto_pool_(config.pool_capacity == 0),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  check_storage_fits(screen().area() * 4, "the head image of screen " + screen().str());
  gpu_->heads = GlStorage(screen().area() * 4);
  allocate_pool(config_.pool_capacity);
  if (config_.buffer.saturation) gpu_->saturation = GlStorage(screen().area() * 4);
  if (kind_.sort_pass) {
    gpu_->sort = std::make_unique<SortPass>(kind_.technique, mode, bindings);
    declare_pass({GlPassStage::Sort, to_string(kind_.technique) + " sort pass", [this](GlPassContext& c) {
                    c.report.sort = gpu_->sort->run(screen(), clock_mode(c.options));
                  }});
  }
}

GlLinkedLists::~GlLinkedLists() = default;

std::uint64_t GlLinkedLists::page_per_pixel(Extent screen) const {
  return std::max<std::uint64_t>(screen.area(), 1) * kind_.page_nodes;
}

bool GlLinkedLists::fit_automatic_size(const TechniqueConfig& wanted) {
  const std::uint64_t fitted = std::min<std::uint64_t>(wanted.pool_capacity, max_storage_bytes() / sizeof(glm::uvec2));
  resize_pool(fitted);
  return fitted != wanted.pool_capacity;
}

void GlLinkedLists::allocate_pool(std::uint64_t nodes) {
  TechniqueConfig c = config_;
  c.pool_capacity = nodes;
  c.validate();
  check_storage_fits(nodes * sizeof(glm::uvec2), "a node pool of " + std::to_string(nodes) + " nodes");
  gpu_->nodes = GlStorage();  // the old pool goes first: the new one may need its memory
  gpu_->links = GlStorage();
  gpu_->nodes = GlStorage(nodes * sizeof(glm::uvec2));
  gpu_->links = GlStorage(nodes * 4);
  config_.pool_capacity = nodes;
}

void GlLinkedLists::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  const std::uint64_t from = this->screen().area(), to = screen.area();
  // The pool holds fragments, which grow with the area: scaled by its ratio
  // (rounded up; the automatic pool at least a page per pixel, as a fresh
  // one starts), or kept when the scaled pool is beyond the limits.
  const std::uint64_t scaled = (config_.pool_capacity * to + from - 1) / from;
  next.pool_capacity = std::max<std::uint64_t>(scaled, auto_pool_ ? page_per_pixel(screen) : 1);
  if (!pool_limit(next.pool_capacity).empty()) next.pool_capacity = config_.pool_capacity;
  next.validate();
  if (const std::string why = pool_limit(next.pool_capacity); !why.empty()) throw GlError(why);
  check_storage_fits(to * 4, "the head image of screen " + screen.str());
  // Made before the old ones go (fresh's members free them on a throw).
  Gpu fresh;
  fresh.heads = GlStorage(to * 4);
  if (next.pool_capacity != config_.pool_capacity) {
    fresh.nodes = GlStorage(next.pool_capacity * sizeof(glm::uvec2));
    fresh.links = GlStorage(next.pool_capacity * 4);
  }
  if (next.buffer.saturation) fresh.saturation = GlStorage(to * 4);
  check_gl_errors("resizing the lists' screen");
  gpu_->heads = std::move(fresh.heads);
  gpu_->saturation = std::move(fresh.saturation);
  if (fresh.nodes) {
    gpu_->nodes = std::move(fresh.nodes);
    gpu_->links = std::move(fresh.links);
  }
  config_ = next;
  // The last request was made on the old screen: SPEC 8's rule waits for a
  // frame of the new one.
  last_requested_ = 0;
}

void GlLinkedLists::resize_pool(std::uint64_t nodes) {
  if (nodes != config_.pool_capacity) allocate_pool(nodes);
}

void GlLinkedLists::write_params(GlParams& p) const { write_technique_params(config_, p); }

void GlLinkedLists::bind() const {
  const GlBindings& b = bindings();
  gpu_->heads.bind_storage(b.heads);
  gpu_->nodes.bind_storage(b.nodes);
  gpu_->links.bind_storage(b.links);
  gpu_->saturation.bind_storage(b.saturation);
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
  if (!(options.adaptive || auto_pool_) || !report.sized_by) return;
  // SPEC 8's rule on the pool (ResizePolicy): its use is the nodes the
  // latest complete frame asked for, dropped ones included.
  const std::uint64_t next = options.policy.next(config_.pool_capacity, report.sized_by->nodes);
  if (next == config_.pool_capacity) return;
  if (!pool_limit(next).empty()) {
    report.resize_limited = true;
    return;
  }
  allocate_pool(next);
  report.resized = true;
}

void GlLinkedLists::before_gather() {
  gpu_->heads.zero();  // the node counter is zeroed with the driver's tallies
  gpu_->saturation.zero();
}

void GlLinkedLists::gathered(std::span<const std::uint32_t> counter_words, FrameReport& report) {
  // The node counter counted every node asked for, dropped ones included
  // (in pages for paged lists).
  report.nodes_requested = counter_words[HABUFFER_COUNTER_NODES];
  last_requested_ = report.nodes_requested;
}

bool GlLinkedLists::grow(const FrameReport& report, const GlFrameOptions& options) {
  // The counter counted every node asked for: a pool of that size holds the frame.
  const std::uint64_t next = config_.grown(options.policy, growth_need(report)).pool_capacity;
  if (!pool_limit(next).empty()) return false;
  allocate_pool(next);
  return true;
}

std::uint64_t GlLinkedLists::memory_bytes() const {
  return bytes_of(gpu_->heads, gpu_->nodes, gpu_->links, gpu_->saturation);
}

std::unique_ptr<FragmentBuffer> GlLinkedLists::read_back() const {
  const std::vector<std::uint32_t> heads = gpu_->heads.read_words(screen().area());
  const std::vector<glm::uvec2> entries = gpu_->nodes.read<glm::uvec2>(config_.pool_capacity);
  const std::vector<std::uint32_t> links = gpu_->links.read_words(config_.pool_capacity);
  return kind_.import(config_, heads, entries, links, last_requested_);
}

}  // namespace habuffer::gl
