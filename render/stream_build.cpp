#include "habuffer/render/stream_build.h"

#include <chrono>
#include <optional>
#include <utility>

#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/gl_info.h"

namespace habuffer {

TechniqueBuild build_technique_on_gl(const TechniqueConfig& config, const OffsetSource& offsets,
                                     std::span<const Fragment> fragments, const ResizePolicy& policy,
                                     std::uint32_t max_attempts, GlBuildInfo* info) {
  check_on_screen(fragments, config.buffer.screen);
  const gl::GlInfo gl_info = gl::query_gl_info();
  const std::optional<gl::AtomicMode> mode = gl::chosen_atomic_mode(gl_info, config.buffer.layout);
  if (!mode) throw gl::GlError("--layout 64 on the GPU path: this OpenGL has no 64-bit shader types (GL_ARB_gpu_shader_int64)");
  // Lossless mode's rule, build_technique's (lossless_attempts): asked before
  // the first gather, since the GPU does not stop between its gathers to
  // look; a stream it stops fails every attempt, so both paths decide alike.
  AttemptLimit limit = lossless_attempts(config, fragments, max_attempts);
  gl::GlFrameOptions frame_options;
  frame_options.policy = policy;
  frame_options.max_attempts = limit.attempts;
  // The CPU's table for an unset one (the screen: build_technique's), so both
  // paths build the same lists; the driver would otherwise size it from a count.
  TechniqueConfig gl_config = config;
  gl_config.buffer.table = config.buffer.table_or_screen();
  gl::GlFrameDriver gpu(gl::make_gl_technique(gl_config, offsets, *mode), frame_options);
  // A pool of 0: the library's automatic pool, sized as the CPU's from the
  // stream's length (no counting gather; grown at once on a drop).
  if (gpu.counts_next_frame()) (void)gpu.size_for(fragments.size());
  gl::ComputeInserter inserter(gpu);
  const auto t0 = std::chrono::steady_clock::now();
  gl::FrameReport report = inserter.insert(fragments);
  if (info) {
    info->build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    info->atomic_mode = gl::to_string(*mode);
    info->renderer = gl_info.renderer;
    info->deferred = report.deferred;
    info->resume_rounds = report.resume_rounds;
    info->cut_short_retries = report.cut_short_retries;
  }
  // The too-deep pixel only where the first gather failed, as on the CPU (which asks after it).
  if (report.counters.failures() == 0) limit.too_deep.reset();
  return TechniqueBuild{gpu.technique().read_back(), report.counters, std::move(report.attempts),
                        report.growth_limited, std::move(limit.too_deep)};
}

}  // namespace habuffer
