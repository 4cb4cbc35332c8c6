#include "gl_build.h"

#include <optional>

#include "habuffer/csv.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/render/stream_build.h"

namespace habuffer::cli {
TechniqueBuild build_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("--path gl: no usable OpenGL: ") + e.what());
  }
  if (!gl::chosen_atomic_mode(gl::query_gl_info(), options.config.layout))
    throw DataError("--path gl --layout 64: this OpenGL has no 64-bit shader types (GL_ARB_gpu_shader_int64)");
  GlBuildInfo info;
  TechniqueBuild built = build_technique_on_gl(technique_config(options), options.offsets, fragments, options.policy,
                                               options.max_attempts, &info);
  timing.build_ms = info.build_ms;
  timing.gl_atomic_mode = info.atomic_mode;
  timing.gl_renderer = info.renderer;
  timing.gl_deferred = info.deferred;
  timing.gl_resume_rounds = info.resume_rounds;
  timing.gl_cut_short_retries = info.cut_short_retries;
  return built;
}

BuildResult build_ha_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  return ha_build_result(build_on_gl(options, fragments, timing));
}

}  // namespace habuffer::cli
