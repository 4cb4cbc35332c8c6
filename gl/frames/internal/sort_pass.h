// The sort pass of the techniques that sort after the gather (linked lists,
// fixed arrays; GP5's post-sort): one compute invocation per pixel sorts
// its list in place and merges identical entries, counting them.
#pragma once

#include "gpu_timer.h"
#include "habuffer/extent.h"
#include "habuffer/gl/frame_report.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/technique.h"

namespace habuffer::gl {

class SortPass {
 public:
  SortPass(Technique technique, AtomicMode mode, const GlBindings& bindings);
  // Needs every buffer bound and the caller's state guard.
  PassTiming run(Extent screen, ClockMode clock);

 private:
  ShaderProgram program_;
  GpuTimer timer_;
};

}  // namespace habuffer::gl
