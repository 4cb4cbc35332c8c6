#include "habuffer/gl/techniques/blended/gl_blended_image.h"

#include <epoxy/gl.h>

#include "habuffer/gl/gl_technique.h"
#include "gl_state_guard.h"
#include "pixel_store.h"
#include "habuffer/techniques/blended/blended_image.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/technique_params.h"

namespace habuffer::gl {

struct GlBlendedImage::Gpu {
  GLuint framebuffer = 0;
  GlTexture accum, revealage;           // attachments 0 and 1 (revealage: wboit only)
  GlStorage accum_copy, revealage_copy;  // their storage-buffer copies, read by the resolve
  MadeOn made_on;
  ~Gpu() {
    if (made_on.current()) glDeleteFramebuffers(1, &framebuffer);  // not another context's (gl_context.h)
  }
};

namespace {

void check_framebuffer_fits(Extent screen) {
  GLint width = 0, height = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &width);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &height);
  if (screen.x > static_cast<std::uint32_t>(width) || screen.y > static_cast<std::uint32_t>(height))
    throw GlError("the blended accumulators of screen " + screen.str() + " exceed this OpenGL's largest framebuffer " +
                  std::to_string(width) + "x" + std::to_string(height));
}

// One attachment into its storage-buffer copy, row after row as the resolve
// indexes it (x + y * width).
void copy_target(const GlTexture& texture, GLenum format, const GlStorage& buffer) {
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer.id());
  glGetTextureImage(texture.id(), 0, format, GL_FLOAT, static_cast<GLsizei>(texture.bytes()), nullptr);
}

}  // namespace

GlBlendedImage::GlBlendedImage(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings)
    : GlTechnique(config.technique, mode, bindings, config.buffer.screen, config.buffer.samples),  // records only: no GL yet
      config_(BlendedImage::checked_config(config)),
      gpu_(std::make_unique<Gpu>()) {
  check_framebuffer_fits(screen());
  const std::uint64_t pixels = screen().area();
  check_storage_fits(pixels * 16, "the blended accumulators of screen " + screen().str());
  gpu_->accum = GlTexture(GL_RGBA32F, screen(), 16);
  gpu_->accum_copy = GlStorage(pixels * 16);
  glCreateFramebuffers(1, &gpu_->framebuffer);
  glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT0, gpu_->accum.id(), 0);
  GLenum draw[2] = {GL_COLOR_ATTACHMENT0, GL_NONE};
  if (weighted()) {
    gpu_->revealage = GlTexture(GL_R32F, screen(), 4);
    gpu_->revealage_copy = GlStorage(pixels * 4);
    glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT1, gpu_->revealage.id(), 0);
    draw[1] = GL_COLOR_ATTACHMENT1;
  } else {
    gpu_->revealage_copy = GlStorage(4);  // bound for the resolve's block; never read
  }
  glNamedFramebufferDrawBuffers(gpu_->framebuffer, 2, draw);
  if (const GLenum status = glCheckNamedFramebufferStatus(gpu_->framebuffer, GL_DRAW_FRAMEBUFFER);
      status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("the " + to_string(technique()) + " accumulators' framebuffer is not complete (status " +
                  std::to_string(status) + ")");
  reset();
  check_gl_errors("creating the blended accumulators");
  declare_pass({GlPassStage::Gather, "the " + to_string(technique()) + " accumulators",
                [this](GlPassContext&) { enter_gather(); }, [this] { leave_gather(); }, gpu_->framebuffer});
}

GlBlendedImage::~GlBlendedImage() = default;

void GlBlendedImage::change_screen(Extent screen) {
  TechniqueConfig next = config_;
  next.buffer.screen = screen;
  next = BlendedImage::checked_config(next);
  check_framebuffer_fits(screen);
  const std::uint64_t pixels = screen.area();
  check_storage_fits(pixels * 16, "the blended accumulators of screen " + screen.str());
  // New attachments and copies first; the framebuffer object stays the same
  // (a host may hold gather_framebuffer()), its attachments replaced by name
  // (no binding changes), and back to the old ones if it is not complete.
  GlTexture accum(GL_RGBA32F, screen, 16), revealage;
  GlStorage accum_copy(pixels * 16), revealage_copy;
  if (weighted()) {
    revealage = GlTexture(GL_R32F, screen, 4);
    revealage_copy = GlStorage(pixels * 4);
  }
  glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT0, accum.id(), 0);
  if (weighted()) glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT1, revealage.id(), 0);
  if (const GLenum status = glCheckNamedFramebufferStatus(gpu_->framebuffer, GL_DRAW_FRAMEBUFFER);
      status != GL_FRAMEBUFFER_COMPLETE) {
    glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT0, gpu_->accum.id(), 0);
    if (weighted()) glNamedFramebufferTexture(gpu_->framebuffer, GL_COLOR_ATTACHMENT1, gpu_->revealage.id(), 0);
    throw GlError("the " + to_string(technique()) + " accumulators' framebuffer of screen " + screen.str() +
                  " is not complete (status " + std::to_string(status) + ")");
  }
  gpu_->accum = std::move(accum);
  gpu_->accum_copy = std::move(accum_copy);
  if (weighted()) {
    gpu_->revealage = std::move(revealage);
    gpu_->revealage_copy = std::move(revealage_copy);
  }
  config_ = next;
  reset();  // the accumulators' empty values
  check_gl_errors("resizing the blended accumulators");
}

void GlBlendedImage::write_params(GlParams& p) const {
  write_technique_params(config_, p);
}

void GlBlendedImage::bind() const {
  gpu_->accum_copy.bind_storage(bindings().accum);
  gpu_->revealage_copy.bind_storage(bindings().revealage);
}

void GlBlendedImage::reset() {
  // glClearTexImage ignores the colour masks and the scissor the host may
  // have set, not its unpack state, through which it reads the clear value.
  const NeutralUnpack unpack;
  const float accum[4] = {0.0f, 0.0f, 0.0f, weighted() ? 0.0f : 1.0f};
  glClearTexImage(gpu_->accum.id(), 0, GL_RGBA, GL_FLOAT, accum);
  if (weighted()) {
    const float revealage = 1.0f;
    glClearTexImage(gpu_->revealage.id(), 0, GL_RED, GL_FLOAT, &revealage);
  }
}

void GlBlendedImage::enter_gather() const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gpu_->framebuffer);
  glDisable(GL_COLOR_LOGIC_OP);  // a logic op would replace blending
  for (GLuint d = 0; d < (weighted() ? 2u : 1u); ++d) {
    glEnablei(GL_BLEND, d);
    glColorMaski(d, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendEquationSeparatei(d, GL_FUNC_ADD, GL_FUNC_ADD);
  }
  if (weighted()) {
    glBlendFunci(0, GL_ONE, GL_ONE);                   // accum += (c a w, a w)
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);  // revealage *= 1 - a
  } else {
    // (C, T) = (a c + (1 - a) C, (1 - a) T) from the output (a c, a).
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
  }
}

void GlBlendedImage::leave_gather() const {
  GlStateGuard::prepare_pack();  // inside the driver's guard, which restores the host's
  copy_target(gpu_->accum, GL_RGBA, gpu_->accum_copy);
  if (weighted()) copy_target(gpu_->revealage, GL_RED, gpu_->revealage_copy);
}

std::uint64_t GlBlendedImage::memory_bytes() const {
  return bytes_of(gpu_->accum, gpu_->revealage, gpu_->accum_copy, gpu_->revealage_copy);
}

std::unique_ptr<FragmentBuffer> GlBlendedImage::read_back() const {
  const std::uint64_t pixels = screen().area();
  const std::vector<glm::vec4> accum = gpu_->accum_copy.read<glm::vec4>(pixels);
  const std::vector<float> revealage = gpu_->revealage_copy.read<float>(weighted() ? pixels : 0);
  auto image = std::make_unique<BlendedImage>(config_);
  image->import_state(accum, revealage);
  return image;
}

}  // namespace habuffer::gl
