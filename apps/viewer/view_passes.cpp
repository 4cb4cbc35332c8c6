#include "view_passes.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <string>

#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "view_shaders.h"

namespace habuffer::view {
namespace {

std::string hex(unsigned value) {
  char text[16];
  std::snprintf(text, sizeof text, "%04X", value);
  return text;
}

std::string gather_header(const gl::GlFrameDriver& driver, bool count_pixels) {
  for (unsigned p : driver.bindings().storage_points())
    if (p == kCountsBinding)
      throw gl::GlError("habuffer-view's counts buffer (binding " + std::to_string(kCountsBinding) +
                        ") collides with the library's points");
  std::string h = "#define V_BINDING_COUNTS " + std::to_string(kCountsBinding) + "\n";
  if (driver.technique().samples() > 1) h += "#define V_SAMPLES " + std::to_string(driver.technique().samples()) + "\n";
  if (driver.needs_call_count()) h += "#define V_COUNT_CALLS\n";
  if (count_pixels) h += "#define V_COUNT_PIXELS\n";
  return h;
}

unsigned texture(GLenum target, GLenum format, Extent s, std::uint32_t samples) {
  GLuint t = 0;
  glCreateTextures(target, 1, &t);
  if (target == GL_TEXTURE_2D_MULTISAMPLE)
    glTextureStorage2DMultisample(t, static_cast<GLsizei>(samples), format, static_cast<GLsizei>(s.x),
                                  static_cast<GLsizei>(s.y), GL_TRUE);
  else
    glTextureStorage2D(t, 1, format, static_cast<GLsizei>(s.x), static_cast<GLsizei>(s.y));
  return t;
}

unsigned framebuffer(std::initializer_list<unsigned> colours, unsigned depth, const char* what) {
  GLuint f = 0;
  glCreateFramebuffers(1, &f);
  std::vector<GLenum> draw;
  for (unsigned c : colours) {
    const auto a = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + draw.size());
    glNamedFramebufferTexture(f, a, c, 0);
    draw.push_back(a);
  }
  if (depth != 0) glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, depth, 0);
  glNamedFramebufferDrawBuffers(f, static_cast<GLsizei>(draw.size()), draw.data());
  const GLenum status = glCheckNamedFramebufferStatus(f, GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &f);
    throw gl::GlError(std::string("the ") + what + " framebuffer is not complete (status 0x" + hex(status) + ")");
  }
  return f;
}

// The opaque pass's fragment shader: with shadows, the lookup's head first.
std::string opaque_source(const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows) {
  const std::string head = shadows != nullptr ? gl::light_lookup_shader_head(*shadows, driver.mode()) + "#define R_SHADOWS\n"
                                              : std::string("#version 450 core\n");
  return head + kShading + kOpaqueFragment;
}

// The gather: the driver's module, the lookup with shadows, then the shading and ours.
std::string gather_source(const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows, bool count_pixels) {
  std::string s = driver.module_source(gl::ShaderStage::Fragment, gather_header(driver, count_pixels));
  if (shadows != nullptr) s += gl::light_lookup_part(*shadows, driver.mode()) + "#define R_SHADOWS\n";
  return s + kShading + kGatherFragment;
}

// glGetTextureImage's byte count is a GLsizei: refuse a read that does not fit it.
GLsizei read_bytes(Extent screen, std::uint64_t bytes_per_pixel) {
  const std::uint64_t bytes = screen.area() * bytes_per_pixel;
  if (bytes > static_cast<std::uint64_t>(INT32_MAX))
    throw gl::GlError("the " + screen.str() + " image (" + std::to_string(bytes) +
                      " bytes) is beyond one read-back of 2 GiB");
  return static_cast<GLsizei>(bytes);
}

// The transmittance map's shader: render's shadow_map.frag.glsl after the lookup.
std::string transmittance_source(const gl::GlFrameDriver& driver, const gl::GlLightBindings& shadows) {
  return gl::light_lookup_shader_head(shadows, driver.mode()) + "#define R_SHADOWS\n" + kShading + kShadowMapFragment;
}

}  // namespace

ViewPasses::ViewPasses(const GpuMeshes& meshes, const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows,
                       bool count_pixels)
    : meshes_(meshes),
      screen_(driver.screen()),
      samples_(driver.technique().samples()),
      technique_framebuffer_(driver.technique().gather_framebuffer()),
      opaque_program_(gl::ShaderProgram::graphics(kSceneVertex, opaque_source(driver, shadows), "habuffer-view opaque pass")),
      gather_program_(gl::ShaderProgram::graphics(kSceneVertex, gather_source(driver, shadows, count_pixels),
                                                  "habuffer-view gather")),
      count_pixels_(count_pixels) {
  // The images one by one: a throw part way deletes those made (release).
  try {
    make_images(driver, shadows);
  } catch (...) {
    release();
    throw;
  }
}

void ViewPasses::make_images(const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows) {
  gl::check_viewport_fits(screen_);
  gl::check_samples_fit(samples_);
  colour_ = texture(GL_TEXTURE_2D, GL_RGBA32F, screen_, 1);
  t_ = texture(GL_TEXTURE_2D, GL_R32F, screen_, 1);
  if (samples_ > 1) {
    ms_colour_ = texture(GL_TEXTURE_2D_MULTISAMPLE, GL_RGBA32F, screen_, samples_);
    ms_t_ = texture(GL_TEXTURE_2D_MULTISAMPLE, GL_R32F, screen_, samples_);
    ms_depth_ = texture(GL_TEXTURE_2D_MULTISAMPLE, GL_DEPTH_COMPONENT32F, screen_, samples_);
    opaque_framebuffer_ = framebuffer({ms_colour_, ms_t_}, ms_depth_, "opaque pass's");
    resolved_framebuffer_ = framebuffer({colour_, t_}, 0, "opaque resolve's");
  } else {
    depth_ = texture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, screen_, 1);
    opaque_framebuffer_ = framebuffer({colour_, t_}, depth_, "opaque pass's");
  }
  // The gather writes no colour: a framebuffer of no attachments, of the
  // screen's size and the buffer's samples at fixed locations (sample s of
  // gl_SampleMaskIn is sample s of the opaque t).
  glCreateFramebuffers(1, &gather_framebuffer_);
  glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH, static_cast<GLint>(screen_.x));
  glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, static_cast<GLint>(screen_.y));
  if (samples_ > 1) {
    glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_SAMPLES, static_cast<GLint>(samples_));
    glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_FIXED_SAMPLE_LOCATIONS, GL_TRUE);
  }
  image_ = texture(GL_TEXTURE_2D, GL_RGBA32F, screen_, 1);
  image_framebuffer_ = framebuffer({image_}, 0, "scene image's");
  counts_ = gl::create_buffer((1 + 2 * screen_.area()) * sizeof(std::uint32_t));
  if (shadows != nullptr && samples_ == 1) {
    transmittance_program_.emplace(
        gl::ShaderProgram::graphics(kSceneVertex, transmittance_source(driver, *shadows), "habuffer-view light T map"));
    transmittance_ = texture(GL_TEXTURE_2D, GL_R32F, screen_, 1);
    transmittance_framebuffer_ = framebuffer({transmittance_}, depth_, "light T map's");
  }
  gather_program_.set("v_screen_width", screen_.x);
}

ViewPasses::~ViewPasses() { release(); }

void ViewPasses::release() {
  const GLuint framebuffers[] = {opaque_framebuffer_, resolved_framebuffer_, gather_framebuffer_, image_framebuffer_,
                                 transmittance_framebuffer_};
  glDeleteFramebuffers(5, framebuffers);
  const GLuint textures[] = {colour_, t_, depth_, ms_colour_, ms_t_, ms_depth_, image_, transmittance_};
  glDeleteTextures(8, textures);
  gl::delete_buffer(counts_);
}

void ViewPasses::draw_depth_tested(unsigned framebuffer, const gl::ShaderProgram& program, const Camera& camera,
                                   bool transparent_too) const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  meshes_.draw(program, camera, true);
  if (transparent_too) meshes_.draw(program, camera, false);
  glDisable(GL_DEPTH_TEST);
}

void ViewPasses::draw_opaque(const Camera& camera, glm::vec3 background) {
  const float bg[4] = {background.x, background.y, background.z, 1.0f};
  const float none[4] = {2.0f, 0.0f, 0.0f, 0.0f};  // t beyond every fragment's
  glClearNamedFramebufferfv(opaque_framebuffer_, GL_COLOR, 0, bg);
  glClearNamedFramebufferfv(opaque_framebuffer_, GL_COLOR, 1, none);
  glClearNamedFramebufferfi(opaque_framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  draw_depth_tested(opaque_framebuffer_, opaque_program_, camera, false);
  if (samples_ > 1) {
    // The per-pixel backgrounds: each attachment's samples box-filtered.
    const auto w = static_cast<GLint>(screen_.x), h = static_cast<GLint>(screen_.y);
    for (GLenum a : {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1}) {
      glNamedFramebufferReadBuffer(opaque_framebuffer_, a);
      glNamedFramebufferDrawBuffer(resolved_framebuffer_, a);
      glBlitNamedFramebuffer(opaque_framebuffer_, resolved_framebuffer_, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT,
                             GL_NEAREST);
    }
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void ViewPasses::gather(const Camera& camera) {
  gl::zero_buffer(counts_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding, counts_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, technique_framebuffer_ != 0 ? technique_framebuffer_ : gather_framebuffer_);
  glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
  glBindTextureUnit(0, samples_ > 1 ? ms_t_ : t_);
  meshes_.draw(gather_program_, camera, false);
  glBindTextureUnit(0, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding, 0);
}

std::vector<std::uint32_t> ViewPasses::transmittance_map(const Camera& camera) {
  if (!transmittance_program_) return {};
  const float none[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(transmittance_framebuffer_, GL_COLOR, 0, none);
  glClearNamedFramebufferfi(transmittance_framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  draw_depth_tested(transmittance_framebuffer_, *transmittance_program_, camera, true);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  const GLsizei bytes = read_bytes(screen_, sizeof(float));
  std::vector<float> t(screen_.area());
  glGetTextureImage(transmittance_, 0, GL_RED, GL_FLOAT, bytes, t.data());
  std::vector<std::uint32_t> out(t.size());
  for (std::size_t i = 0; i < t.size(); ++i)
    out[i] = t[i] < 0.0f ? 0u : 1u + static_cast<std::uint32_t>(std::lround(254.0f * std::min(t[i], 1.0f)));
  return out;
}

std::uint64_t ViewPasses::calls() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return gl::read_words(counts_, 1).at(0);
}

std::vector<std::uint32_t> ViewPasses::read_pixel_fragments() const {
  if (!count_pixels_) return {};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<std::uint32_t> words = gl::read_words(counts_, 1 + 2 * screen_.area());
  std::vector<std::uint32_t> out(screen_.area());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = words[1 + 2 * i];
  return out;
}

Image ViewPasses::read_image() const {
  const GLsizei bytes = read_bytes(screen_, sizeof(glm::vec4));
  Image image{screen_, std::vector<glm::vec4>(screen_.area())};
  glGetTextureImage(image_, 0, GL_RGBA, GL_FLOAT, bytes, image.pixels.data());
  return image;
}

std::vector<glm::vec3> ViewPasses::read_opaque_colour() const {
  const GLsizei bytes = read_bytes(screen_, sizeof(glm::vec4));
  std::vector<glm::vec4> rgba(screen_.area());
  glGetTextureImage(colour_, 0, GL_RGBA, GL_FLOAT, bytes, rgba.data());
  std::vector<glm::vec3> out(rgba.size());
  for (std::size_t i = 0; i < rgba.size(); ++i) out[i] = glm::vec3(rgba[i]);
  return out;
}

}  // namespace habuffer::view
