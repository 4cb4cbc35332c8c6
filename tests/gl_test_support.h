// Helpers of the GL test files: one headless context per process and the
// CPU-side twin of a GPU buffer.
#pragma once

#include "habuffer/gl/compute_inserter.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_ha_buffer.h"
#include "test_support.h"

namespace habuffer::test {

inline gl::EglContext& gl_context() {
  static gl::EglContext ctx;  // one per process: llvmpipe contexts are costly
  ctx.make_current();
  return ctx;
}

inline OffsetSource random_offsets(std::uint64_t seed) {
  OffsetSource s;
  s.generator = OffsetGenerator::Random;
  s.seed = seed;
  return s;
}

inline Layout layout_of(gl::AtomicMode mode) { return mode == gl::AtomicMode::Native32 ? Layout::L32 : Layout::L64; }

// The CPU path's buffer for the GPU buffer's current table and offsets, fed `fragments`.
inline HaBuffer cpu_twin(const gl::GlHaBuffer& gpu, std::span<const Fragment> fragments) {
  HaBuffer cpu(gpu.config(), gpu.offsets());
  cpu.insert(fragments);
  return cpu;
}

}  // namespace habuffer::test
