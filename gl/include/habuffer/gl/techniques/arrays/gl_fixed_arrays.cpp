#include "habuffer/gl/techniques/arrays/gl_fixed_arrays.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl_params.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "sort_pass.h"

namespace habuffer::gl {
struct GlFixedArrays::Gpu {
  GLuint counts = 0, layers = 0;
  std::unique_ptr<SortPass> sort;
  ~Gpu() {
    for (GLuint* b : {&counts, &layers}) delete_buffer(*b);
  }
};

GlFixedArrays::GlFixedArrays(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(Technique::Arrays, mode, bindings, validated_as(config, Technique::Arrays).buffer.screen),
      config_(validated_as(config, Technique::Arrays)),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  check_storage_fits(screen().area() * 4, "the counters of screen " + screen().str());
  gpu_->counts = create_buffer(screen().area() * 4);
  allocate_layers(config_.layers);
  gpu_->sort = std::make_unique<SortPass>(Technique::Arrays, mode, bindings);
}

GlFixedArrays::~GlFixedArrays() = default;

void GlFixedArrays::allocate_layers(std::uint32_t layers) {
  TechniqueConfig c = config_;
  c.layers = layers;
  c.validate();
  const std::uint64_t bytes = std::uint64_t{layers} * screen().area() * sizeof(glm::uvec2);
  check_storage_fits(bytes, std::to_string(layers) + " layers of screen " + screen().str());
  delete_buffer(gpu_->layers);
  gpu_->layers = create_buffer(bytes);
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
  Gpu fresh;  // made before the old ones go; its destructor frees them on a throw
  fresh.counts = create_buffer(pixels * 4);
  fresh.layers = create_buffer(bytes);
  check_gl_errors("resizing the arrays' screen");
  std::swap(gpu_->counts, fresh.counts);
  std::swap(gpu_->layers, fresh.layers);
  config_ = next;
  most_arrived_ = 0;
}

void GlFixedArrays::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlFixedArrays::bind() const {
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings().table, gpu_->counts);    // HABUFFER_BINDING_COUNTS
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings().max_age, gpu_->layers);  // HABUFFER_BINDING_LAYERS
}

void GlFixedArrays::before_gather() { zero_buffer(gpu_->counts); }

PassTiming GlFixedArrays::after_gather(bool finish_timing) { return gpu_->sort->run(screen(), finish_timing); }

bool GlFixedArrays::grow(const FrameReport& report, const GlFrameOptions& options) {
  // K as large as the deepest pixel: the regather keeps every fragment.
  const TechniqueConfig next = config_.grown(options.policy, 0, report.most_arrived);
  if (!next.limit().empty() ||
      std::uint64_t{next.layers} * screen().area() * sizeof(glm::uvec2) > max_storage_bytes())
    return false;
  allocate_layers(next.layers);
  return true;
}

std::uint64_t GlFixedArrays::memory_bytes() const {
  return screen().area() * 4 + capacity() * sizeof(glm::uvec2);
}

std::unique_ptr<FragmentBuffer> GlFixedArrays::read_back() const {
  auto arrays = std::make_unique<FixedArrays>(config_);
  const std::vector<std::uint32_t> counts = read_words(gpu_->counts, screen().area());
  std::vector<glm::uvec2> layers(capacity());
  glGetNamedBufferSubData(gpu_->layers, 0, static_cast<GLsizeiptr>(layers.size() * sizeof(glm::uvec2)), layers.data());
  arrays->import_state(counts, layers, most_arrived_);
  return arrays;
}

}  // namespace habuffer::gl
