#include "habuffer/render/gl_floors.h"

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer {
namespace {

BufferConfig screen_config(Extent screen) {
  BufferConfig c;
  c.screen = screen;
  return c;
}

gl::AtomicMode l64_mode() {
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl::query_gl_info(), Layout::L64);
  if (!mode) throw gl::GlError("the GL floors need 64-bit shader types (GL_ARB_gpu_shader_int64)");
  return *mode;
}

}  // namespace

GlFloors::GlFloors(const Scene& scene, Extent screen)
    : camera_(frame_scene(scene, {scene.default_yaw, scene.default_pitch, 45.0f}, screen)),
      module_owner_(screen_config(screen), OffsetSource{}, l64_mode()),
      renderer_(scene, screen, module_owner_) {
  (void)pass(true);
  (void)pass(false);
}

double GlFloors::pass(bool blend) {
  renderer_.draw_opaque(camera_, glm::vec3(1.0f));
  module_owner_.bind();
  return blend ? renderer_.blend_floor(camera_) : renderer_.atomic_floor(camera_);
}

}  // namespace habuffer
