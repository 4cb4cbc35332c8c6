#include "sort_pass.h"

#include <epoxy/gl.h>

#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

SortPass::SortPass(Technique technique, AtomicMode mode, const GlBindings& bindings)
    : program_(ShaderProgram::compute(sort_compute(technique, mode, bindings), to_string(technique) + " sort pass")) {}

PassTiming SortPass::run(Extent screen, ClockMode clock) {
  glUseProgram(program_.id());
  PassClock pass_clock(timer_, clock);
  glDispatchCompute((screen.x + 7) / 8, (screen.y + 7) / 8, 1);
  // The resolve and read-backs see the sorted lists.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto [wall, gpu] = pass_clock.stop();
  return {wall, gpu};
}

}  // namespace habuffer::gl
