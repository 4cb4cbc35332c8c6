#include "shadow_light.h"

#include <epoxy/gl.h>

#include <chrono>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer::view {
namespace {

Scene light_scene(const Scene& scene) {
  Scene s = scene;
  for (Mesh& m : s.meshes) m.insert_opaque = true;  // the light sees opaque meshes as records of opacity 1
  return s;
}

BufferConfig light_config(Extent size) {
  BufferConfig c;
  c.screen = size;
  c.layout = Layout::L64;  // the lookup reads colour and opacity
  c.table = size;          // grown by lossless gathers until nothing is dropped
  return c;
}

gl::GlLightMapping mapping_of(const LightView& v) {
  return {v.camera.view, v.camera.projection, v.camera.near_plane, v.camera.far_plane};
}

gl::AtomicMode light_mode() {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode) throw gl::GlError("shadows: the light buffer's 64-bit records need GL_ARB_gpu_shader_int64");
  return *mode;
}

}  // namespace

ShadowLight::ShadowLight(const Scene& scene, glm::vec3 direction, Extent size, const gl::GlBindings& view_bindings)
    : direction_(direction),
      view_(frame_light(scene, spot_along(scene, direction, 60.0f, size))),
      meshes_(light_scene(scene)) {
  gl::GlFrameOptions o;
  o.max_attempts = 16;
  o.light = mapping_of(view_);  // the gather's t is the light's, as the lookup computes it
  buffer_ = std::make_unique<gl::GlHaBuffer>(light_config(size), OffsetSource{}, light_mode(), o);
  passes_ = std::make_unique<ViewPasses>(meshes_, *buffer_);
  // render's bias rule at its default slope (2): surfaces up to atan(2) from facing the light never shadow themselves.
  figures_.bias_codes = shadow_bias_codes(view_, 2.0f, light_config(size).record_layout().depth_bits());
  lookup_ = std::make_unique<gl::GlShadowLookup>(buffer_->container(), mapping_of(view_), figures_.bias_codes,
                                                 view_bindings);
  figures_.size = size;
}

ShadowLight::~ShadowLight() = default;

void ShadowLight::build() {
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  passes_->draw_opaque(view_.camera, glm::vec3(1.0f));  // nothing is opaque: every t is "none"
  const gl::FrameReport r = buffer_->frame([&] { passes_->gather(view_.camera); }, [&] { return passes_->calls(); });
  glFinish();
  figures_.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  figures_.table = buffer_->table();
  figures_.fragments = r.counters.fragments;
  figures_.stored = r.counters.stored();
  figures_.failures = r.counters.failures();
  figures_.attempts = static_cast<std::uint32_t>(r.attempts.size());
}

void ShadowLight::bind() { lookup_->bind(); }

}  // namespace habuffer::view
