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

std::string to_string(AtomicMode mode) {
  switch (mode) {
    case AtomicMode::Native32: return "native32";
    case AtomicMode::Native64: return "native64";
    case AtomicMode::Emulated64: return "emulated64";
  }
  return "?";
}

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

std::vector<AtomicMode> runnable_atomic_modes(const GlInfo& info) {
  std::vector<AtomicMode> modes{AtomicMode::Native32};
  if (info.int64_types && info.atomic_int64) modes.push_back(AtomicMode::Native64);
  if (info.int64_types) modes.push_back(AtomicMode::Emulated64);
  return modes;
}

std::optional<AtomicMode> atomic_mode_override() {
  const char* env = std::getenv("HABUFFER_ATOMIC_MODE");
  if (env == nullptr || *env == '\0') return std::nullopt;
  for (AtomicMode m : {AtomicMode::Native32, AtomicMode::Native64, AtomicMode::Emulated64})
    if (to_string(m) == env) return m;
  throw GlError("HABUFFER_ATOMIC_MODE='" + std::string(env) + "' is not native32, native64 or emulated64");
}

std::optional<AtomicMode> chosen_atomic_mode(const GlInfo& info, Layout layout) {
  const auto forced = atomic_mode_override();
  if (forced && (*forced == AtomicMode::Native32) != (layout == Layout::L32)) {
    // A mode the layout cannot run is never replaced quietly: 32-bit atomics
    // cannot hold a 64-bit record (refused); a 64-bit mode forced beside a
    // 32-bit layout leaves it its one mode (said once).
    if (layout == Layout::L64)
      throw GlError("HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " does not fit layout " + to_string(layout) +
                    ": 64-bit records run native64 or emulated64 (unset the variable, force one of those, or use "
                    "32-bit records)");
    log_once("warning: HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " does not apply to layout " + to_string(layout) +
             ": 32-bit records run native32, their only mode");
  } else if (forced) {
    const auto runnable = runnable_atomic_modes(info);
    if (std::find(runnable.begin(), runnable.end(), *forced) == runnable.end())
      throw GlError("HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " cannot run on this OpenGL (" + info.renderer +
                    (*forced == AtomicMode::Native64 ? "): no GL_NV_shader_atomic_int64" : "): no 64-bit shader types"));
    return forced;
  }
  if (layout == Layout::L32) return AtomicMode::Native32;
  if (info.int64_types && info.atomic_int64) return AtomicMode::Native64;
  if (info.int64_types) return AtomicMode::Emulated64;
  return std::nullopt;
}

}  // namespace habuffer::gl
