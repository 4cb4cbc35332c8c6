#include "habuffer/gl/techniques/arrays/gl_fixed_arrays.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "habuffer/gl/gl_technique.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "sort_pass.h"

namespace habuffer::gl {
struct GlFixedArrays::Gpu {
  GlStorage counts, layers;
  std::unique_ptr<SortPass> sort;
};

GlFixedArrays::GlFixedArrays(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(Technique::Arrays, mode, bindings, validated_as(config, Technique::Arrays).buffer.screen,
                  config.buffer.samples),
      config_(validated_as(config, Technique::Arrays)),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  check_storage_fits(screen().area() * 4, "the counters of screen " + screen().str());
  gpu_->counts = GlStorage(screen().area() * 4);
  allocate_layers(config_.layers);
  gpu_->sort = std::make_unique<SortPass>(Technique::Arrays, mode, bindings);
  declare_pass({GlPassStage::Sort, "the arrays' sort pass", [this](GlPassContext& c) {
                  c.report.sort = gpu_->sort->run(screen(), clock_mode(c.options));
                }});
}

GlFixedArrays::~GlFixedArrays() = default;

void GlFixedArrays::allocate_layers(std::uint32_t layers) {
  TechniqueConfig c = config_;
  c.layers = layers;
  c.validate();
  const std::uint64_t bytes = std::uint64_t{layers} * screen().area() * sizeof(glm::uvec2);
  check_storage_fits(bytes, std::to_string(layers) + " layers of screen " + screen().str());
  gpu_->layers = GlStorage();  // the old layers go first: the new ones may need their memory
  gpu_->layers = GlStorage(bytes);
  config_.layers = layers;
}

void GlFixedArrays::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  next.validate();  // K slots per pixel within 32-bit indices
  const std::uint64_t pixels = screen.area();
  check_storage_fits(pixels * 4, "the counters of screen " + screen.str());
  const std::uint64_t bytes = std::uint64_t{config_.layers} * pixels * sizeof(glm::uvec2);
  check_storage_fits(bytes, std::to_string(config_.layers) + " layers of screen " + screen.str());
  Gpu fresh;  // made before the old ones go; its members free them on a throw
  fresh.counts = GlStorage(pixels * 4);
  fresh.layers = GlStorage(bytes);
  check_gl_errors("resizing the arrays' screen");
  gpu_->counts = std::move(fresh.counts);
  gpu_->layers = std::move(fresh.layers);
  config_ = next;
  most_arrived_ = 0;
}

void GlFixedArrays::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlFixedArrays::bind() const {
  gpu_->counts.bind_storage(bindings().counts);
  gpu_->layers.bind_storage(bindings().layers);
}

void GlFixedArrays::before_gather() { gpu_->counts.zero(); }

void GlFixedArrays::gathered(std::span<const std::uint32_t> counter_words, FrameReport& report) {
  // The most fragments a pixel received, tallied when some pixel overflowed.
  report.most_arrived = counter_words[HABUFFER_COUNTER_MOST_ARRIVED];
  most_arrived_ = report.most_arrived;
}

bool GlFixedArrays::grow(const FrameReport& report, const GlFrameOptions& options) {
  // K as large as the deepest pixel: the regather keeps every fragment.
  const TechniqueConfig next = config_.grown(options.policy, growth_need(report));
  if (!next.limit().empty() ||
      std::uint64_t{next.layers} * screen().area() * sizeof(glm::uvec2) > max_storage_bytes())
    return false;
  allocate_layers(next.layers);
  return true;
}

std::uint64_t GlFixedArrays::memory_bytes() const { return bytes_of(gpu_->counts, gpu_->layers); }

std::unique_ptr<FragmentBuffer> GlFixedArrays::read_back() const {
  auto arrays = std::make_unique<FixedArrays>(config_);
  const std::vector<std::uint32_t> counts = gpu_->counts.read_words(screen().area());
  const std::vector<glm::uvec2> layers = gpu_->layers.read<glm::uvec2>(capacity());
  arrays->import_state(counts, layers, most_arrived_);
  return arrays;
}

}  // namespace habuffer::gl
