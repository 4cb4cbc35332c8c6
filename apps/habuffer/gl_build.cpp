#include "gl_build.h"

#include <chrono>
#include <optional>

#include "habuffer/csv.h"
#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"

namespace habuffer::cli {
TechniqueBuild build_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("--path gl: no usable OpenGL: ") + e.what());
  }
  const BufferConfig& c = options.config;
  const gl::GlInfo info = gl::query_gl_info();
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(info, c.layout);
  if (!mode) throw DataError("--path gl --layout 64: this OpenGL has no 64-bit shader types (GL_ARB_gpu_shader_int64)");
  gl::GlFrameOptions frame_options;
  frame_options.policy = options.policy;
  frame_options.max_attempts = options.max_attempts;
  const TechniqueConfig config = technique_config(options);
  gl::GlFrameDriver gpu(gl::make_gl_technique(config, options.offsets, *mode), frame_options);
  // --pool auto: the library's automatic pool, sized as the CPU's (grown at once on a drop).
  if (uses_pool(config.technique) && config.pool_capacity == 0) {
    TechniqueConfig wanted = config;
    wanted.pool_capacity = options.policy.automatic(fragments.size());
    gpu.technique().fit_automatic_size(wanted);
  }
  gl::ComputeInserter inserter(gpu);
  const auto t0 = std::chrono::steady_clock::now();
  gl::FrameReport report = inserter.insert(fragments);
  timing.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  timing.gl_atomic_mode = gl::to_string(*mode);
  timing.gl_renderer = info.renderer;
  timing.gl_deferred = report.deferred;
  timing.gl_resume_rounds = report.resume_rounds;
  timing.gl_cut_short_retries = report.cut_short_retries;
  return TechniqueBuild{gpu.technique().read_back(), report.counters, std::move(report.attempts), false, std::nullopt};
}

BuildResult build_ha_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing) {
  return ha_build_result(build_on_gl(options, fragments, timing));
}

}  // namespace habuffer::cli
