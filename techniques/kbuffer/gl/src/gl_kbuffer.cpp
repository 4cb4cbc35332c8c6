#include "habuffer/gl/techniques/kbuffer/gl_kbuffer.h"

#include <epoxy/gl.h>

#include <utility>

#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/technique_params.h"

namespace habuffer::gl {
struct GlKBuffer::Gpu {
  GlStorage slots, locks, occupancy, limits;
  std::unique_ptr<ShaderProgram> count;
};

GlKBuffer::GlKBuffer(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(Technique::KBuffer, mode, bindings, validated_as(config, Technique::KBuffer).buffer.screen,
                  config.buffer.samples),
      config_(validated_as(config, Technique::KBuffer)),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.buffer.layout);
  allocate_layers(config_.layers);
  const std::uint64_t pixels = screen().area();
  if (config_.occupancy) {
    check_storage_fits(pixels * config_.occupancy_words * 4, "an occupancy map of " +
                                                                 std::to_string(config_.occupancy_words) + " words per pixel");
    gpu_->occupancy = GlStorage(pixels * config_.occupancy_words * 4);
    gpu_->limits = GlStorage(pixels * 4);
    gpu_->count = std::make_unique<ShaderProgram>(
        ShaderProgram::compute(kbuffer_count_compute(mode, bindings), "k-buffer count pass"));
    declare_pass({GlPassStage::Fill, "the k-buffer's count pass", [this](GlPassContext&) { count_limits(); }});
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
  gpu_->slots = GlStorage();  // the old layers go first: the new ones may need their memory
  gpu_->locks = GlStorage();
  gpu_->slots = GlStorage(slots * word_bytes());
  // Zeroed: every critical section leaves its lock at 0 again.
  if (mode() == AtomicMode::Emulated64) gpu_->locks = GlStorage(emulated64_lock_words(slots) * 4);
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
  Gpu fresh;  // made before the old ones go; its members free them on a throw
  fresh.slots = GlStorage(slots * word_bytes());
  if (mode() == AtomicMode::Emulated64) fresh.locks = GlStorage(emulated64_lock_words(slots) * 4);
  if (config_.occupancy) {
    fresh.occupancy = GlStorage(pixels * config_.occupancy_words * 4);
    fresh.limits = GlStorage(pixels * 4);
  }
  check_gl_errors("resizing the k-buffer's screen");
  gpu_->slots = std::move(fresh.slots);
  gpu_->locks = std::move(fresh.locks);
  gpu_->occupancy = std::move(fresh.occupancy);
  gpu_->limits = std::move(fresh.limits);
  config_ = next;
}

void GlKBuffer::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlKBuffer::bind() const {
  const GlBindings& b = bindings();
  gpu_->slots.bind_storage(b.slots);
  gpu_->locks.bind_storage(b.locks);
  gpu_->occupancy.bind_storage(b.occupancy);
  gpu_->limits.bind_storage(b.limits);
}

void GlKBuffer::before_gather() {
  gpu_->slots.zero();
  gpu_->occupancy.zero();
}

void GlKBuffer::reset() { gpu_->slots.zero(); }

void GlKBuffer::count_limits() const {
  glUseProgram(gpu_->count->id());
  glDispatchCompute((screen().x + 7) / 8, (screen().y + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

bool GlKBuffer::grow(const FrameReport&, const GlFrameOptions& options) {
  const TechniqueConfig next = config_.grown(options.policy, GrowthNeed{});
  if (!next.limit().empty() || std::uint64_t{next.layers} * screen().area() * word_bytes() > max_storage_bytes())
    return false;
  allocate_layers(next.layers);
  return true;
}

std::uint64_t GlKBuffer::memory_bytes() const {
  return bytes_of(gpu_->slots, gpu_->locks, gpu_->occupancy, gpu_->limits);
}

std::unique_ptr<FragmentBuffer> GlKBuffer::read_back() const {
  auto kb = std::make_unique<KBuffer>(config_);
  const std::vector<std::uint32_t> words = gpu_->slots.read_words(capacity() * word_bytes() / 4);
  const std::vector<std::uint32_t> limits =
      config_.occupancy ? gpu_->limits.read_words(screen().area()) : std::vector<std::uint32_t>{};
  kb->import_state(words, limits);
  return kb;
}

}  // namespace habuffer::gl
