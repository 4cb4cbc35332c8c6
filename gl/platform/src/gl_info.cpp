#include "habuffer/gl/gl_context.h"
#include "habuffer/gl/gl_info.h"

#include <algorithm>
#include <cstdlib>

#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"

#include <epoxy/gl.h>

namespace habuffer::gl {
namespace {

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? s : "";
}

}  // namespace

GlInfo query_gl_info() {
  require_context("query_gl_info");
  GlInfo i;
  i.vendor = gl_string(GL_VENDOR);
  i.renderer = gl_string(GL_RENDERER);
  i.version = gl_string(GL_VERSION);
  i.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  i.int64_types = epoxy_has_gl_extension("GL_ARB_gpu_shader_int64");
  i.atomic_int64 = epoxy_has_gl_extension("GL_NV_shader_atomic_int64");
  i.khr_debug = epoxy_has_gl_extension("GL_KHR_debug") || epoxy_gl_version() >= 43;
  i.occlusion_query2 = epoxy_has_gl_extension("GL_ARB_occlusion_query2") || epoxy_gl_version() >= 33;
  GLint64 ssbo = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
  i.max_ssbo_bytes = ssbo;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &i.max_framebuffer_width);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &i.max_framebuffer_height);
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &i.max_compute_work_groups_x);
  i.software_rasterizer =
      i.renderer.find("llvmpipe") != std::string::npos || i.renderer.find("softpipe") != std::string::npos;
  return i;
}

AtomicSupport atomic_support(const GlInfo& info) {
  return {info.int64_types, info.atomic_int64, "OpenGL", info.renderer, "GL_ARB_gpu_shader_int64",
          "GL_NV_shader_atomic_int64"};
}

std::vector<AtomicMode> runnable_atomic_modes(const GlInfo& info) {
  return habuffer::runnable_atomic_modes(atomic_support(info));
}

std::optional<AtomicMode> atomic_mode_override() {
  try {
    return habuffer::atomic_mode_override();
  } catch (const std::invalid_argument& e) {
    throw GlError(e.what());
  }
}

std::optional<AtomicMode> chosen_atomic_mode(const GlInfo& info, Layout layout) {
  try {
    return habuffer::chosen_atomic_mode(atomic_support(info), layout, [](const std::string& m) { log_once(m); });
  } catch (const std::invalid_argument& e) {
    throw GlError(e.what());
  }
}

}  // namespace habuffer::gl
