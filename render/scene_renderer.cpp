#include "habuffer/render/scene_renderer.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <chrono>
#include <stdexcept>

#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/glsl_sources.h"
#include "record_gather.h"
#include "render_shaders.h"

namespace habuffer {
namespace {

constexpr unsigned kPixelFragmentsBinding = 10, kPixelCulledBinding = 11, kRejectedBinding = 12;

// The gather shader's own defines: its binding points, what it counts and,
// on a multisampled screen, its samples (R_SAMPLES: each sample of a
// fragment is tested against its own opaque depth, the rest inserted with
// the fragment's coverage mask).
std::string gather_header(const gl::GlBindings& b, SceneRenderer::GatherCounts counts, std::uint32_t samples) {
  for (unsigned p : b.storage_points())
    if (p == kPixelFragmentsBinding || p == kPixelCulledBinding || p == kRejectedBinding)
      throw gl::GlError("the renderer's shader-storage points 10-12 collide with the library's");
  std::string h = "#define R_BINDING_PIXEL_FRAGMENTS " + std::to_string(kPixelFragmentsBinding) +
                  "\n#define R_BINDING_PIXEL_CULLED " + std::to_string(kPixelCulledBinding) +
                  "\n#define R_BINDING_REJECTED " + std::to_string(kRejectedBinding) + "\n";
  if (counts.fragments) h += "#define R_COUNT_FRAGMENTS\n";
  if (counts.culled) h += "#define R_COUNT_CULLED\n";
  if (samples > 1) h += "#define R_SAMPLES " + std::to_string(samples) + "\n";
  return h;
}

std::string gather_code() { return std::string(render::kShading) + render::kGatherFragment; }

// Translucent shadows: the light lookup and R_SHADOWS (shading.glsl) before
// the shading, after the technique's module (the gather) or in a head of its
// own (the passes without one).
std::string shadow_defines(const ShadowReceiving& shadows) {
  return std::string("#define R_SHADOWS\n") + (shadows.pcf ? "#define R_SHADOWS_PCF\n" : "");
}
std::string shadow_part(const std::optional<ShadowReceiving>& shadows, gl::AtomicMode mode) {
  return shadows ? gl::light_lookup_part(shadows->bindings, mode) + shadow_defines(*shadows) : std::string();
}
std::string standalone_head(const std::optional<ShadowReceiving>& shadows, gl::AtomicMode mode) {
  return shadows ? gl::light_lookup_shader_head(shadows->bindings, mode) + shadow_defines(*shadows)
                 : std::string("#version 450 core\n");
}

std::string opaque_source(const std::optional<ShadowReceiving>& shadows, gl::AtomicMode mode) {
  return standalone_head(shadows, mode) + render::kShading + render::kOpaqueFragment;
}

std::string shadow_map_source(const ShadowReceiving& shadows, gl::AtomicMode mode) {
  return standalone_head(shadows, mode) + render::kShading + render::kShadowMapFragment;
}

bool same_view(const Camera& a, const Camera& b) {
  return a.view == b.view && a.projection == b.projection && a.near_plane == b.near_plane && a.far_plane == b.far_plane;
}

}  // namespace

SceneRenderer::GatherCounts SceneRenderer::GatherCounts::for_driver(const gl::GlFrameDriver& buffer) {
  return {buffer.needs_call_count(), true};
}

SceneRenderer::Sources SceneRenderer::shader_sources(gl::AtomicMode mode, const gl::GlBindings& b, Technique technique,
                                                     GatherCounts counts, std::optional<ShadowReceiving> shadows,
                                                     std::uint32_t samples) {
  Sources s;
  s.vertex = render::kSceneVertex;
  s.opaque_fragment = opaque_source(shadows, mode);
  s.gather_fragment =
      gl::technique_module(technique, mode, b, gl::ShaderStage::Fragment, gather_header(b, counts, samples)) +
                      shadow_part(shadows, mode) + gather_code();
  if (shadows) s.shadow_map_fragment = shadow_map_source(*shadows, mode);
  return s;
}

SceneRenderer::SceneRenderer(const Scene& scene, Extent screen, const gl::GlFrameDriver& buffer)
    : SceneRenderer(scene, screen, buffer, GatherCounts::for_driver(buffer)) {}

SceneRenderer::SceneRenderer(const Scene& scene, Extent screen, const gl::GlFrameDriver& buffer, GatherCounts counts,
                             std::optional<ShadowReceiving> shadows)
    : screen_(screen),
      counts_(counts),
      buffer_(buffer),
      opaque_program_(
          gl::ShaderProgram::graphics(render::kSceneVertex, opaque_source(shadows, buffer.mode()), "opaque pass")),
      gather_program_(gl::ShaderProgram::graphics(
          render::kSceneVertex,
          buffer.module_source(gl::ShaderStage::Fragment,
                               gather_header(buffer.bindings(), counts, buffer.technique().samples())) +
              shadow_part(shadows, buffer.mode()) + gather_code(),
          "gather pass")),
      blend_program_(gl::ShaderProgram::graphics(
          render::kSceneVertex, std::string("#version 450 core\n") + render::kShading + render::kBlendFragment,
          "blend floor")),
      atomic_floor_program_(gl::ShaderProgram::graphics(
          render::kSceneVertex,
          std::string("#version 450 core\n#define R_BINDING_PIXEL_FRAGMENTS 10\n") + render::kShading +
              render::kAtomicFloorFragment,
          "atomic floor")),
      technique_framebuffer_(buffer.technique().gather_framebuffer()),
      samples_(buffer.technique().samples()) {
  check_screen_fits(screen, "screen");  // the textures and renderbuffer below; before any GL object is made
  gl::check_samples_fit(samples_);      // the multisampled images below, exactly that many samples
  if (samples_ > 1 && shadows)
    throw gl::GlError("translucent shadows are not drawn on a multisampled screen (" + std::to_string(samples_) +
                      " samples): render with one sample per pixel for shadows");
  for (const Mesh& m : scene.meshes) {
    GpuMesh g;
    g.count = static_cast<std::int32_t>(m.indices.size());
    g.colour = m.colour;
    g.opacity = m.opacity;
    g.opaque = m.opaque();
    g.vertices = gl::create_buffer(m.positions.size() * sizeof(glm::vec3), m.positions.data());
    g.indices = gl::create_buffer(m.indices.size() * 4, m.indices.data());
    glCreateVertexArrays(1, &g.vertex_array);
    glVertexArrayVertexBuffer(g.vertex_array, 0, g.vertices, 0, sizeof(glm::vec3));
    glVertexArrayElementBuffer(g.vertex_array, g.indices);
    glEnableVertexArrayAttrib(g.vertex_array, 0);
    glVertexArrayAttribFormat(g.vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(g.vertex_array, 0, 0);
    meshes_.push_back(g);
  }
  const auto w = static_cast<GLsizei>(screen.x), h = static_cast<GLsizei>(screen.y);
  glCreateTextures(GL_TEXTURE_2D, 1, &colour_);
  glTextureStorage2D(colour_, 1, GL_RGBA32F, w, h);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  glTextureStorage2D(depth_, 1, GL_R32F, w, h);
  glCreateFramebuffers(1, &opaque_framebuffer_);
  if (samples_ > 1) {
    // The opaque pass is multisampled: its colour and t per sample; colour_
    // and depth_ get their box-filtered resolve (the backgrounds, per pixel).
    const auto s = static_cast<GLsizei>(samples_);
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &ms_colour_);
    glTextureStorage2DMultisample(ms_colour_, s, GL_RGBA32F, w, h, GL_TRUE);
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &ms_depth_);
    glTextureStorage2DMultisample(ms_depth_, s, GL_R32F, w, h, GL_TRUE);
    glCreateRenderbuffers(1, &ms_depth_buffer_);
    glNamedRenderbufferStorageMultisample(ms_depth_buffer_, s, GL_DEPTH_COMPONENT32F, w, h);
    glNamedFramebufferTexture(opaque_framebuffer_, GL_COLOR_ATTACHMENT0, ms_colour_, 0);
    glNamedFramebufferTexture(opaque_framebuffer_, GL_COLOR_ATTACHMENT1, ms_depth_, 0);
    glNamedFramebufferRenderbuffer(opaque_framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ms_depth_buffer_);
    glCreateFramebuffers(1, &resolved_framebuffer_);
    glNamedFramebufferTexture(resolved_framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
    glNamedFramebufferTexture(resolved_framebuffer_, GL_COLOR_ATTACHMENT1, depth_, 0);
  } else {
    glCreateRenderbuffers(1, &depth_buffer_);
    glNamedRenderbufferStorage(depth_buffer_, GL_DEPTH_COMPONENT32F, w, h);
    glNamedFramebufferTexture(opaque_framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
    glNamedFramebufferTexture(opaque_framebuffer_, GL_COLOR_ATTACHMENT1, depth_, 0);
    glNamedFramebufferRenderbuffer(opaque_framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer_);
  }
  const GLenum draw[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(opaque_framebuffer_, 2, draw);
  if (glCheckNamedFramebufferStatus(opaque_framebuffer_, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("the opaque pass's framebuffer " + screen.str() + " is not complete");
  glCreateFramebuffers(1, &blend_framebuffer_);
  glNamedFramebufferTexture(blend_framebuffer_, GL_COLOR_ATTACHMENT0, colour_, 0);
  glCreateFramebuffers(1, &gather_framebuffer_);
  glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH, w);
  glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, h);
  if (samples_ > 1) {
    // Sample s of gl_SampleMaskIn at sample s of the opaque depth texture: both at fixed locations.
    glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_SAMPLES, static_cast<GLint>(samples_));
    glNamedFramebufferParameteri(gather_framebuffer_, GL_FRAMEBUFFER_DEFAULT_FIXED_SAMPLE_LOCATIONS, GL_TRUE);
  }
  for (const gl::ShaderProgram* p : {&gather_program_, &atomic_floor_program_}) p->set("r_screen_width", screen.x);
  if (shadows) {
    shadow_program_.emplace(
        gl::ShaderProgram::graphics(render::kSceneVertex, shadow_map_source(*shadows, buffer.mode()), "shadow map pass"));
    glCreateTextures(GL_TEXTURE_2D, 1, &shadow_map_);
    glTextureStorage2D(shadow_map_, 1, GL_R32F, w, h);
    glCreateFramebuffers(1, &shadow_framebuffer_);
    glNamedFramebufferTexture(shadow_framebuffer_, GL_COLOR_ATTACHMENT0, shadow_map_, 0);
    glNamedFramebufferRenderbuffer(shadow_framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer_);
    if (glCheckNamedFramebufferStatus(shadow_framebuffer_, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("the shadow map pass's framebuffer " + screen.str() + " is not complete");
  }
  pixel_fragments_ = gl::create_buffer(screen.area() * 4);
  pixel_culled_ = gl::create_buffer(screen.area() * 4);
  rejected_ = gl::create_buffer(4);
}

SceneRenderer::~SceneRenderer() {
  for (const GpuMesh& g : meshes_) {
    glDeleteVertexArrays(1, &g.vertex_array);
    const GLuint b[] = {g.vertices, g.indices};
    glDeleteBuffers(2, b);
  }
  const GLuint buffers[] = {pixel_fragments_, pixel_culled_, rejected_};
  glDeleteBuffers(3, buffers);
  const GLuint framebuffers[] = {opaque_framebuffer_, gather_framebuffer_, blend_framebuffer_, shadow_framebuffer_,
                                 resolved_framebuffer_};
  glDeleteFramebuffers(5, framebuffers);  // 0 (no shadows, one sample) is ignored
  const GLuint renderbuffers[] = {depth_buffer_, ms_depth_buffer_};
  glDeleteRenderbuffers(2, renderbuffers);
  const GLuint textures[] = {colour_, depth_, shadow_map_, ms_colour_, ms_depth_};
  glDeleteTextures(5, textures);
}

void SceneRenderer::draw_meshes(const gl::ShaderProgram& program, const Camera& camera, bool opaque) const {
  glUseProgram(program.id());
  glProgramUniformMatrix4fv(program.id(), glGetUniformLocation(program.id(), "r_view"), 1, GL_FALSE,
                            glm::value_ptr(camera.view));
  glProgramUniformMatrix4fv(program.id(), glGetUniformLocation(program.id(), "r_projection"), 1, GL_FALSE,
                            glm::value_ptr(camera.projection));
  program.set("r_near", camera.near_plane);
  program.set("r_far", camera.far_plane);
  for (const GpuMesh& g : meshes_) {
    if (g.opaque != opaque) continue;
    program.set("r_colour", g.colour.x, g.colour.y, g.colour.z);
    program.set("r_opacity", g.opacity);
    glBindVertexArray(g.vertex_array);
    glDrawElements(GL_TRIANGLES, g.count, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

void SceneRenderer::draw_opaque(const Camera& camera, glm::vec3 background) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, opaque_framebuffer_);
  glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
  const float bg[4] = {background.x, background.y, background.z, 1.0f};
  const float none[4] = {2.0f, 0.0f, 0.0f, 0.0f};  // t beyond every fragment's
  glClearNamedFramebufferfv(opaque_framebuffer_, GL_COLOR, 0, bg);
  glClearNamedFramebufferfv(opaque_framebuffer_, GL_COLOR, 1, none);
  glClearNamedFramebufferfi(opaque_framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  draw_meshes(opaque_program_, camera, true);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  if (samples_ > 1) {
    // The backgrounds per pixel: each attachment's samples box-filtered.
    const auto w = static_cast<GLint>(screen_.x), h = static_cast<GLint>(screen_.y);
    for (GLenum a : {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1}) {
      glNamedFramebufferReadBuffer(opaque_framebuffer_, a);
      glNamedFramebufferDrawBuffer(resolved_framebuffer_, a);
      glBlitNamedFramebuffer(opaque_framebuffer_, resolved_framebuffer_, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT,
                             GL_NEAREST);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  opaque_ = camera;
}

void SceneRenderer::bind_counts() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPixelFragmentsBinding, pixel_fragments_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPixelCulledBinding, pixel_culled_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRejectedBinding, rejected_);
}

void SceneRenderer::gather(const Camera& camera) {
  // Zeroed each time: a frame may gather twice.
  if (counts_.fragments) gl::zero_buffer(pixel_fragments_);
  if (counts_.culled) gl::zero_buffer(pixel_culled_);
  gl::zero_buffer(rejected_);
  bind_counts();
  // The blended baselines' inserts blend into the technique's framebuffer.
  draw_transparent(gather_program_, camera, technique_framebuffer_ != 0 ? technique_framebuffer_ : gather_framebuffer_);
  latest_ = camera;
  if (counts_.fragments) counted_ = camera;
}

void SceneRenderer::count(const Camera& camera) {
  gl::zero_buffer(pixel_fragments_);
  gl::zero_buffer(rejected_);
  buffer_.bind();  // the module's blocks, which the pass declares though it reads none
  bind_counts();
  gather_program_.set("r_count_only", 1u);
  draw_transparent(gather_program_, camera, gather_framebuffer_);  // writes no colour: it discards every fragment
  gather_program_.set("r_count_only", 0u);
  latest_ = counted_ = camera;
}

std::uint64_t SceneRenderer::count_fragments(const Camera& camera) {
  count(camera);
  return inserted();
}

void SceneRenderer::draw_transparent(const gl::ShaderProgram& program, const Camera& camera, unsigned framebuffer) const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  // Every transparent pass rejects what lies behind the opaque surfaces (the
  // gather per sample on a multisampled screen; the floors per pixel).
  glBindTextureUnit(0, samples_ > 1 && &program == &gather_program_ ? ms_depth_ : depth_);
  draw_meshes(program, camera, false);
  glBindTextureUnit(0, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

namespace {

double finished_ms(std::chrono::steady_clock::time_point t0) {
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

double SceneRenderer::blend_floor(const Camera& camera) {
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  draw_transparent(blend_program_, camera, blend_framebuffer_);  // the opaque colour alone: its depth image is read
  glDisable(GL_BLEND);
  return finished_ms(t0);
}

double SceneRenderer::atomic_floor(const Camera& camera) {
  gl::zero_buffer(pixel_fragments_);
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPixelFragmentsBinding, pixel_fragments_);
  draw_transparent(atomic_floor_program_, camera, gather_framebuffer_);
  latest_ = counted_ = camera;  // its atomic adds are the per-pixel counts
  return finished_ms(t0);
}

double SceneRenderer::shadow_map_pass(const Camera& camera) {
  if (!shadow_program_) throw std::logic_error("shadow_map_pass on a renderer made without shadows");
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadow_framebuffer_);
  glViewport(0, 0, static_cast<GLsizei>(screen_.x), static_cast<GLsizei>(screen_.y));
  const float none[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(shadow_framebuffer_, GL_COLOR, 0, none);
  glClearNamedFramebufferfi(shadow_framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  draw_meshes(*shadow_program_, camera, true);
  draw_meshes(*shadow_program_, camera, false);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  return finished_ms(t0);
}

std::vector<float> SceneRenderer::read_opaque_depth() const {
  std::vector<float> out(screen_.area());
  glGetTextureImage(depth_, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
  return out;
}

std::vector<float> SceneRenderer::read_shadow_map() const {
  if (!shadow_program_) return {};
  std::vector<float> out(screen_.area());
  glGetTextureImage(shadow_map_, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
  return out;
}

std::vector<glm::vec3> SceneRenderer::read_opaque_colour() const {
  std::vector<glm::vec3> out(screen_.area());
  glGetTextureImage(colour_, 0, GL_RGB, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(glm::vec3)), out.data());
  return out;
}

std::vector<std::uint32_t> SceneRenderer::read_pixel_fragments() {
  if (latest_ && !(counted_ && same_view(*counted_, *latest_))) {
    // The count rejects against the opaque depth image, which must still be the gather's.
    if (!opaque_ || !same_view(*opaque_, *latest_))
      throw std::logic_error("per-pixel counts of a gather whose opaque pass was drawn over since");
    count(*latest_);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return gl::read_words(pixel_fragments_, screen_.area());
}

std::vector<std::uint32_t> SceneRenderer::read_pixel_culled() const {
  if (!counts_.culled) return {};
  return gl::read_words(pixel_culled_, screen_.area());
}

std::uint64_t SceneRenderer::inserted() {
  std::uint64_t n = 0;
  for (std::uint32_t c : read_pixel_fragments()) n += c;
  return n;
}

std::uint64_t SceneRenderer::read_rejected() const { return gl::read_words(rejected_, 1)[0]; }

}  // namespace habuffer
