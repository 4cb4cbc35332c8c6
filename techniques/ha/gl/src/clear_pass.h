// The paper's clear pass: a quad per tile of the table on an attachment-less
// framebuffer, one fragment per slot; fragments of empty slots are discarded
// and the others zero their slot, so a GL_SAMPLES_PASSED query counts the
// stored records at almost no cost. Tables beyond the framebuffer limits
// (16384² on llvmpipe) are cleared in tiles under the same query. While a
// host's own occlusion query is active (GL_SAMPLES_PASSED, GL_ANY_SAMPLES_
// PASSED[_CONSERVATIVE] around frame(): GL allows one at a time, and ours
// would end the host's), the pass counts with an atomic add instead and
// discards every fragment, so the host's query counts none of ours.
#pragma once

#include <cstdint>

#include "gpu_timer.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/extent.h"
#include "habuffer/gl/gl_bindings.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shader_program.h"

namespace habuffer::gl {

class ClearPass {
 public:
  // Compiles the pass for the buffer's atomic mode and binding points.
  ClearPass(AtomicMode mode, const GlBindings& bindings);
  ~ClearPass();
  ClearPass(const ClearPass&) = delete;
  ClearPass& operator=(const ClearPass&) = delete;

  struct Result {
    std::uint64_t stored = 0;
    double wall_ms = 0.0, gpu_ms = 0.0;
  };
  // Needs the buffers bound and the caller's state guard; `tile` 0: the limits.
  // writes false: count only. finish: wait for the pass before stopping the clock.
  // result_buffer non-zero: the count is written there (8 bytes at offset 0)
  // when the GPU has it, without waiting, and Result::stored is 0.
  // count false: no occlusion query at all (a count nobody reads); Result::stored is 0.
  Result run(Extent table, std::uint32_t tile, bool writes, ClockMode clock, unsigned result_buffer = 0,
             bool count = true);
  // Bytes of the buffers it allocated (the atomic route's count).
  [[nodiscard]] std::uint64_t bytes() const { return atomic_count_.bytes(); }

 private:
  ShaderProgram program_;
  GpuTimer timer_;
  unsigned framebuffer_ = 0, vertex_array_ = 0, query_ = 0;
  MadeOn made_on_;
  GlStorage atomic_count_;      // the count of the atomic route (8 bytes, a query result's layout)
  unsigned stream_point_ = 0;   // where the atomic route binds it (the stream point: unused by the pass)
};

}  // namespace habuffer::gl
