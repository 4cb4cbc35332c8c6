#include "habuffer/gl/techniques/kbuffer/gl_kbuffer.h"

#include <epoxy/gl.h>

#include <utility>

#include "gl_params.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/technique_params.h"

namespace habuffer::gl {
struct GlKBuffer::Gpu {
  GLuint slots = 0, locks = 0, occupancy = 0, limits = 0, saturation = 0;
  std::unique_ptr<ShaderProgram> count;
  ~Gpu() {
    for (GLuint* b : {&slots, &locks, &occupancy, &limits, &saturation}) delete_buffer(*b);
  }
};

GlKBuffer::GlKBuffer(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(Technique::KBuffer, mode, bindings, validated_as(config, Technique::KBuffer).buffer.screen),
      config_(validated_as(config, Technique::KBuffer)),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  allocate_layers(config_.layers);
  const std::uint64_t pixels = screen().area();
  if (config_.occupancy) {
    check_storage_fits(pixels * config_.occupancy_words * 4, "an occupancy map of " +
                                                                 std::to_string(config_.occupancy_words) + " words per pixel");
    gpu_->occupancy = create_buffer(pixels * config_.occupancy_words * 4);
    gpu_->limits = create_buffer(pixels * 4);
    gpu_->count = std::make_unique<ShaderProgram>(
        ShaderProgram::compute(kbuffer_count_compute(mode, bindings), "k-buffer count pass"));
  }
}

GlKBuffer::~GlKBuffer() = default;

std::uint64_t GlKBuffer::word_bytes() const { return config_.buffer.record_layout().word_bytes(); }

void GlKBuffer::allocate_layers(std::uint32_t layers) {
  TechniqueConfig c = config_;
  c.layers = layers;
  c.validate();
  const std::uint64_t slots = std::uint64_t{layers} * screen().area();
  check_storage_fits(slots * word_bytes(), std::to_string(layers) + " k-buffer layers of screen " + screen().str());
  delete_buffer(gpu_->slots);
  delete_buffer(gpu_->locks);
  gpu_->slots = create_buffer(slots * word_bytes());
  if (mode() == AtomicMode::Emulated64) {
    gpu_->locks = create_buffer(emulated64_lock_words(slots) * 4);
    zero_buffer(gpu_->locks);  // every critical section leaves its lock at 0 again
  }
  config_.layers = layers;
}

void GlKBuffer::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  next.validate();  // K slots and the occupancy words per pixel within 32-bit indices
  const std::uint64_t pixels = screen.area(), slots = std::uint64_t{config_.layers} * pixels;
  check_storage_fits(slots * word_bytes(), std::to_string(config_.layers) + " k-buffer layers of screen " + screen.str());
  if (config_.occupancy)
    check_storage_fits(pixels * config_.occupancy_words * 4,
                       "an occupancy map of " + std::to_string(config_.occupancy_words) + " words per pixel");
  Gpu fresh;  // made before the old ones go; its destructor frees them on a throw
  fresh.slots = create_buffer(slots * word_bytes());
  if (mode() == AtomicMode::Emulated64) fresh.locks = create_buffer(emulated64_lock_words(slots) * 4);
  if (config_.occupancy) {
    fresh.occupancy = create_buffer(pixels * config_.occupancy_words * 4);
    fresh.limits = create_buffer(pixels * 4);
  }
  check_gl_errors("resizing the k-buffer's screen");
  for (auto [mine, theirs] : {std::pair{&gpu_->slots, &fresh.slots}, std::pair{&gpu_->locks, &fresh.locks},
                              std::pair{&gpu_->occupancy, &fresh.occupancy}, std::pair{&gpu_->limits, &fresh.limits}})
    std::swap(*mine, *theirs);
  config_ = next;
}

void GlKBuffer::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlKBuffer::bind() const {
  const GlBindings& b = bindings();
  for (const auto& [point, buffer] : {std::pair{b.table, gpu_->slots}, std::pair{b.locks, gpu_->locks},
                                      std::pair{b.max_age, gpu_->occupancy}, std::pair{b.offsets, gpu_->limits}})
    if (buffer != 0) bind_at(GL_SHADER_STORAGE_BUFFER, point, buffer);
}

void GlKBuffer::before_gather() {
  zero_buffer(gpu_->slots);
  if (gpu_->occupancy != 0) zero_buffer(gpu_->occupancy);
}

void GlKBuffer::reset() { zero_buffer(gpu_->slots); }

void GlKBuffer::between_passes() {
  if (!gpu_->count) return;
  glUseProgram(gpu_->count->id());
  glDispatchCompute((screen().x + 7) / 8, (screen().y + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

bool GlKBuffer::grow(const FrameReport&, const GlFrameOptions& options) {
  const TechniqueConfig next = config_.grown(options.policy, 0, 0);
  if (!next.limit().empty() || std::uint64_t{next.layers} * screen().area() * word_bytes() > max_storage_bytes())
    return false;
  allocate_layers(next.layers);
  return true;
}

std::uint64_t GlKBuffer::memory_bytes() const {
  std::uint64_t bytes = capacity() * word_bytes();
  if (mode() == AtomicMode::Emulated64) bytes += emulated64_lock_words(capacity()) * 4;
  if (config_.occupancy) bytes += screen().area() * (std::uint64_t{config_.occupancy_words} + 1) * 4;
  return bytes;
}

std::unique_ptr<FragmentBuffer> GlKBuffer::read_back() const {
  auto kb = std::make_unique<KBuffer>(config_);
  const std::vector<std::uint32_t> words = read_words(gpu_->slots, capacity() * word_bytes() / 4);
  const std::vector<std::uint32_t> limits =
      config_.occupancy ? read_words(gpu_->limits, screen().area()) : std::vector<std::uint32_t>{};
  kb->import_state(words, limits);
  return kb;
}

}  // namespace habuffer::gl
